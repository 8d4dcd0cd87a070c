// Pre-integrated classification: the table against direct evaluation of the segment integral, its
// interpolation error against the table's spacing, the second-order table against quadratic scalars, and
// renders of paper A's linear field (the scalar linear along every ray) against the exact method.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

// A smooth rise and fall of extinction and colour, colours differing per channel.
TransferFunction smoothTransferFunction() {
    return TransferFunction({{0.0, 0.0, 0.0, 0.0, 0.0},
                             {0.3, 1.0, 0.5, 0.2, 2.0},
                             {0.6, 0.2, 1.0, 0.5, 0.5},
                             {1.0, 0.8, 0.1, 1.0, 3.0}},
                            EmissionModel::ColourTimesExtinction);
}

// Zero near both ends, a jump at s = 0.5 and a narrow peak: what pre-integration is for.
TransferFunction jumpingTransferFunction() {
    return TransferFunction({{0.05, 0.0, 0.0, 0.0, 0.0},
                             {0.3, 1.0, 0.4, 0.1, 1.0},
                             {0.5, 1.0, 0.4, 0.1, 1.0},
                             {0.5, 0.1, 0.6, 1.0, 4.0},
                             {0.7, 0.1, 0.6, 1.0, 4.0},
                             {0.72, 1.0, 1.0, 1.0, 20.0},
                             {0.74, 0.1, 0.6, 1.0, 4.0},
                             {0.95, 0.0, 0.0, 0.0, 0.0}},
                            EmissionModel::ColourTimesExtinction);
}

double largestDifference(const SegmentIntegral<double>& a, const SegmentIntegral<double>& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b), std::abs(a.depth - b.depth)});
}

}  // namespace

TEST_CASE("preintegration table: its entries are the direct integrals, bit for bit") {
    for (const TransferFunction& tf : {smoothTransferFunction(), jumpingTransferFunction()}) {
        const PreintegrationTable table(tf, 0.5, 33, 1);
        for (int i = 0; i < 33; i += 4)
            for (int j = 0; j < 33; j += 3) {
                const double front = i / 32.0, back = j / 32.0;
                const SegmentIntegral<double> want = PreintegrationTable::direct(tf, 0.5, front, back, 0.0);
                const SegmentIntegral<double> got = table(front, back, 0.0);
                CHECK(got.r == want.r);
                CHECK(got.g == want.g);
                CHECK(got.b == want.b);
                CHECK(got.depth == want.depth);
            }
    }
    // A segment of constant scalar under a constant extinction: the closed form.
    const TransferFunction flat({{0.0, 0.5, 0.25, 1.0, 2.0}, {1.0, 0.5, 0.25, 1.0, 2.0}},
                                EmissionModel::ColourTimesExtinction);
    const SegmentIntegral<double> v = PreintegrationTable::direct(flat, 0.3, 0.2, 0.7, 0.0);
    CHECK(v.depth == doctest::Approx(0.6).epsilon(1e-14));
    CHECK(v.r == doctest::Approx(0.5 * -std::expm1(-0.6)).epsilon(1e-9));  // the entries' tolerance 1e-10
}

TEST_CASE("preintegration table: the interpolation error falls with the spacing") {
    const TransferFunction tf = smoothTransferFunction();
    const PreintegrationError coarse = PreintegrationTable(tf, 0.5, 17, 1).check(tf);
    const PreintegrationError fine = PreintegrationTable(tf, 0.5, 65, 1).check(tf);
    CHECK(coarse.points == 16 * 16);  // every cell
    CHECK(fine.points == 64 * 64);
    CHECK(coarse.colour > 0.0);
    CHECK(fine.colour > 0.0);
    // Four times the resolution, at least about four times less error: the largest error sits where the
    // diagonal (front = back) crosses a transfer-function point, across whose kink bilinear interpolation
    // is first order in the spacing (second order elsewhere).
    CHECK(coarse.colour / fine.colour > 3.5);
    CHECK(coarse.alpha / fine.alpha > 3.5);
    // The check measures what a lookup does: a point between entries against the direct integral.
    const PreintegrationTable table(tf, 0.5, 17, 1);
    const double front = 7.5 / 16, back = 3.5 / 16;
    const double off = largestDifference(table(front, back, 0.0), PreintegrationTable::direct(tf, 0.5, front, back, 0.0));
    CHECK(off > 0.0);
    CHECK(off <= std::max(coarse.colour, coarse.alpha) * 4.0);  // depth vs alpha: the same order here
}

TEST_CASE("preintegration table: order 2 follows a quadratic scalar that order 1 ignores") {
    const TransferFunction tf = smoothTransferFunction();
    const PreintegrationTable first(tf, 0.5, 129, 1), second(tf, 0.5, 129, 2);
    const double front = 0.21, back = 0.47;
    for (const double delta : {0.004, -0.003}) {
        const SegmentIntegral<double> want = PreintegrationTable::direct(tf, 0.5, front, back, delta);
        const double firstError = largestDifference(first(front, back, delta), want);
        const double secondError = largestDifference(second(front, back, delta), want);
        CHECK(firstError > 1e-4);                     // the midpoint moved the integral
        CHECK(secondError < firstError / 20.0);       // the derivative table follows it
    }
    // Over the cells at growing deviations, the first-order expansion in delta drifts: the measured error
    // grows past what interpolation costs at delta = 0 (the check reports it, where +-1/4 alone hid it).
    const PreintegrationError e = second.check(tf), flat = first.check(tf);
    REQUIRE(e.deltas.size() == 8);  // 0, 1/4, 1 and 4 spacings, 1/8 (16 spacings), 1/4, 1/2, 1 - a spacing
    CHECK(e.points > 7 * 64 * 64);  // more than at 0, +-1/4, +-1 and +-4 spacings alone
    CHECK(e.colour > flat.colour);
    CHECK(e.colourByDelta[4] > 4 * e.colourByDelta[1]);
    CHECK(e.colourByDelta[0] == doctest::Approx(flat.colour).epsilon(0.5));
}

TEST_CASE("preintegration table: sizes and orders outside their ranges are refused") {
    const TransferFunction tf = smoothTransferFunction();
    CHECK_THROWS_WITH_AS(PreintegrationTable(tf, 0.5, 1, 1), "pre-integration table size must be in [2, 1024], got 1",
                         Error);
    CHECK_THROWS_WITH_AS(PreintegrationTable(tf, 0.5, 1025, 1),
                         "pre-integration table size must be in [2, 1024], got 1025", Error);
    CHECK_THROWS_WITH_AS(PreintegrationTable(tf, 0.5, 16, 3), "pre-integration order must be 1 or 2, got 3", Error);
    CHECK_THROWS_AS(PreintegrationTable(tf, 0.0, 16, 1), Error);
}

TEST_CASE("preintegrated render: exact to the table's error on a linear field with a piecewise-linear TF") {
    // Every ray enters and leaves through the x faces (a narrow view along x), where s = 0 and 1 and the
    // transfer function is zero, so the segment Entry Align overshoots the exit by adds exactly nothing.
    const Camera camera(test::cameraSpec({-6.0, 0.1, 0.2}, {0.0, 0.0, 0.0}, 8.0, 12, 12));
    const Scene scene{nullptr, LinearField{}, GridConvention::CellCentred, jumpingTransferFunction()};
    const ExactReference exact = renderExactReference(scene, camera);
    double previous = 0.0;
    for (const int size : {65, 257}) {
        RenderOptions opt;
        opt.integrator = Integrator::Preintegrated;
        opt.samplingRate = 1.0 / 0.5;
        opt.preintegrationSize = size;
        RenderStats stats;
        const Image image = render(scene, camera, opt, &stats);
        REQUIRE(stats.preintegration);
        const PreintegrationError table = stats.preintegration->error;
        // A ray of n segments adds at most n lookups' colour errors, and each depth error moves the rest.
        const double segments = static_cast<double>(stats.samplesPlaced) / static_cast<double>(stats.raysHit) + 1.0;
        const double allowed = segments * (table.colour + table.alpha) + 1e-6;  // float image
        double worst = 0.0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            worst = std::max(worst, std::abs(static_cast<double>(image.pixels[i]) - exact.values[i]));
        CHECK(worst > 1e-6);  // the table's interpolation is visible at this size
        CHECK(worst <= allowed);
        if (previous > 0.0) CHECK(worst < previous / 4.0);  // and falls with the table's spacing
        previous = worst;
    }
}

TEST_CASE("preintegrated render: double and float agree, and the table does not depend on the thread count") {
    const Camera camera(test::cameraSpec({-4.0, 1.5, 2.5}, {0.1, -0.2, 0.0}, 40.0, 10, 8));
    const Scene scene{nullptr, LinearField{}, GridConvention::NodeCentred, jumpingTransferFunction()};
    RenderOptions opt;
    opt.integrator = Integrator::Preintegrated;
    opt.preintegrationSize = 64;
    opt.preintegrationOrder = 2;
    opt.placement = Placement::EntryExitAlignCorner;
    const Image a = render(scene, camera, opt);
    opt.tileSize = 3;
    const Image b = render(scene, camera, opt);
    CHECK(a.pixels == b.pixels);
    opt.precision = Precision::Float;
    const Image c = render(scene, camera, opt);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) CHECK(std::abs(a.pixels[i] - c.pixels[i]) < 1e-5);
}

TEST_CASE("preintegration table: its own empty space is where every lookup is exactly 0, and only there") {
    // Zero below s = 0.05 and above 0.95: lookups with both ends there read only zero entries, except
    // those whose cell reaches the first non-zero entry (interpolation reads a cell's two ends).
    const TransferFunction tf = jumpingTransferFunction();
    for (int order : {1, 2}) {
        const PreintegrationTable table(tf, 1.0, 64, order);
        CHECK(table.isInvisible(0.0, 0.02));
        CHECK(table.isInvisible(0.97, 1.0));
        CHECK(!table.isInvisible(0.0, 0.1));    // reaches the rise after 0.05
        CHECK(!table.isInvisible(0.3, 0.4));    // visible
        CHECK(!table.isInvisible(0.02, 0.97));  // two empty ends, a visible segment between them
        // The leading run: every pair below invisibleBelow() is empty, and the cell after it is not.
        const double below = table.invisibleBelow();
        CHECK(below > 0.02);
        CHECK(below <= 0.05 + 1.0 / 63);
        CHECK(table.isInvisible(0.0, below - 1e-9));
        CHECK(!table.isInvisible(0.0, below + 1.0 / 63));
        // Visible at 0: no scalar, not even one below 0 (clamped onto entry 0), is below the run.
        const TransferFunction visibleAtZero({{0.0, 0.5, 0.5, 0.5, 1.0}, {1.0, 0.5, 0.5, 0.5, 1.0}},
                                             EmissionModel::ColourTimesExtinction);
        CHECK(PreintegrationTable(visibleAtZero, 1.0, 16, order).invisibleBelow() == -std::numeric_limits<double>::infinity());
        // Wherever the test says empty, every lookup there is 0: dense front, back and delta.
        for (double s0 = 0.0; s0 < 1.0; s0 += 1.0 / 128)
            for (double s1 = s0; s1 <= 1.0; s1 += 1.0 / 128) {
                if (!table.isInvisible(s0, s1)) continue;
                for (double front = s0; front <= s1; front += (s1 - s0) / 7 + 1e-9)
                    for (double back = s0; back <= s1; back += (s1 - s0) / 7 + 1e-9)
                        for (double delta : {0.0, 0.01, -0.3}) {
                            const SegmentIntegral<double> v = table(front, back, delta);
                            const SegmentIntegral<float> f = table(float(front), float(back), float(delta));
                            CHECK((v.r == 0 && v.g == 0 && v.b == 0 && v.depth == 0));
                            CHECK((f.r == 0 && f.g == 0 && f.b == 0 && f.depth == 0));
                        }
            }
    }
}

TEST_CASE("preintegration table: order 2's measured error covers every midpoint deviation a render can ask") {
    const TransferFunction tf = jumpingTransferFunction();
    const PreintegrationTable table(tf, 1.0, 64, 2);
    const PreintegrationError e = table.check(tf);
    const double spacing = 1.0 / 63;
    // 0, 1/4, 1, 4 and 16 spacings, 1/8, 1/4 and 1/2, then the largest a cell centre admits, ascending.
    const std::vector<double> want{0.0,  0.25 * spacing, spacing, 4 * spacing,  0.125,
                                   0.25, 16 * spacing,   0.5,     1.0 - spacing};
    REQUIRE(e.deltas.size() == want.size());
    for (std::size_t k = 0; k < want.size(); ++k) CHECK(e.deltas[k] == doctest::Approx(want[k]));
    CHECK(e.deltas == table.checkedDeltas());
    REQUIRE(e.colourByDelta.size() == e.deltas.size());
    REQUIRE(e.alphaByDelta.size() == e.deltas.size());
    CHECK(e.colour == *std::max_element(e.colourByDelta.begin(), e.colourByDelta.end()));
    CHECK(e.alpha == *std::max_element(e.alphaByDelta.begin(), e.alphaByDelta.end()));
    // Every cell is checked at 63 cells: a lookup at any cell centre and checked deviation, the midpoint in
    // [0, 1], is within what the check reports for that deviation.
    int compared = 0;
    for (int a = 0; a < 63; a += 5)
        for (int b = 0; b < 63; b += 7)
            for (std::size_t level = 0; level < e.deltas.size(); ++level)
                for (const double sign : {1.0, -1.0}) {
                    const double front = (a + 0.5) * spacing, back = (b + 0.5) * spacing,
                                 delta = sign * e.deltas[level];
                    const double middle = 0.5 * (front + back) + delta;
                    if (middle < 0.0 || middle > 1.0) continue;
                    const SegmentIntegral<double> got = table(front, back, delta);
                    const SegmentIntegral<double> direct = PreintegrationTable::direct(tf, 1.0, front, back, delta);
                    INFO("front ", front, " back ", back, " delta ", delta);
                    CHECK(std::max({std::abs(got.r - direct.r), std::abs(got.g - direct.g),
                                    std::abs(got.b - direct.b)}) <= e.colourByDelta[level] + 1e-12);
                    CHECK(std::abs(std::expm1(-got.depth) - std::expm1(-direct.depth)) <=
                          e.alphaByDelta[level] + 1e-12);
                    ++compared;
                }
    CHECK(compared > 500);
    // What a render's largest deviation reads: the errors up to the first checked deviation that covers it.
    const auto upTo = [&](std::size_t last) {
        return std::make_pair(*std::max_element(e.colourByDelta.begin(), e.colourByDelta.begin() + last + 1),
                              *std::max_element(e.alphaByDelta.begin(), e.alphaByDelta.begin() + last + 1));
    };
    CHECK(e.upTo(0.0) == upTo(0));
    CHECK(e.upTo(spacing) == upTo(2));
    CHECK(e.upTo(2 * spacing) == upTo(3));
    CHECK(e.upTo(2.0) == upTo(want.size() - 1));
    // A table of one cell checks delta = 0 and its widest deviation, 0 too: once.
    const PreintegrationTable two(tf, 1.0, 2, 2);
    CHECK(two.checkedDeltas() == std::vector<double>{0.0});
    // Order 1 has no deviation to check.
    CHECK(PreintegrationTable(tf, 1.0, 64, 1).check(tf).deltas.empty());
}
