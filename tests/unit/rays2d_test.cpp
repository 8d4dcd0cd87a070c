// Paper A's 2D study: the closed form against an independent quadrature, and the behaviour of
// each placement that Fig. 2 shows.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "libvri/core/rays2d.h"
#include "libvri/report/rays2d_report.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

// I = ∫_0^D g(λ) exp(-∫_0^λ tau) dλ by composite Simpson on the outer integral, with the inner
// integral by Simpson on each panel too, evaluating the field through Rays2D::field (the grid
// reconstruction), not through the closed form's own formulas.
double quadrature(const Rays2D& r, int rayIndex, int panels) {
    const Study2D& s = r.study();
    const double a = s.rayAngleDegrees(rayIndex) * M_PI / 180.0;
    const double c = std::cos(s.rotationRadians), sn = std::sin(s.rotationRadians);
    const glm::dvec2 d(std::cos(a), std::sin(a));
    const glm::dvec2 o = s.eye, dl(c * d.x + sn * d.y, -sn * d.x + c * d.y), ol(c * o.x + sn * o.y, -sn * o.x + c * o.y);
    // entry and exit: scan finely for the interval inside the square, then refine by bisection
    auto inside = [&](double t) { const glm::dvec2 p = ol + t * dl; return std::abs(p.x) <= 1.5 && std::abs(p.y) <= 1.5; };
    double t0 = -1, t1 = -1;
    for (double t = 0; t < 20; t += 1e-3) if (inside(t)) { if (t0 < 0) t0 = t; t1 = t; }
    if (t0 < 0) return 0.0;
    auto refine = [&](double in, double out) { for (int i = 0; i < 100; ++i) { double m = 0.5 * (in + out); (inside(m) ? in : out) = m; } return in; };
    t0 = refine(t0, t0 - 1e-3);
    t1 = refine(t1, t1 + 1e-3);
    auto f = [&](double t) { return r.field(ol + t * dl); };
    // The reconstruction is smooth between the lines through the voxel samples (x = const): split
    // there, then composite Simpson on each piece for both the inner and the outer integral.
    std::vector<double> cuts{t0, t1};
    const bool cell = s.convention == GridConvention::CellCentred;
    for (int i = 0; i < s.gridSize; ++i) {
        const double x = -1.5 + (cell ? (i + 0.5) * 3.0 / s.gridSize : i * 3.0 / (s.gridSize - 1));
        const double t = (x - ol.x) / dl.x;
        if (t > t0 && t < t1) cuts.push_back(t);
    }
    std::sort(cuts.begin(), cuts.end());
    double depth = 0.0, total = 0.0;
    for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
        const double h = (cuts[piece + 1] - cuts[piece]) / panels;
        for (int k = 0; k < panels; ++k) {
            const double a0 = cuts[piece] + k * h, am = a0 + 0.5 * h, a1 = a0 + h;
            const double fa = f(a0), fm = f(am), fb = f(a1);
            const double dm = depth + 0.5 * (h / 2) / 6 * (fa + 4 * f(a0 + 0.25 * h) + fm);  // tau = f / 2
            const double d1 = depth + 0.5 * h / 6 * (fa + 4 * fm + fb);
            total += h / 6 * (fa * std::exp(-depth) + 4 * fm * std::exp(-dm) + fb * std::exp(-d1));
            depth = d1;
        }
    }
    return total;
}

}  // namespace

TEST_CASE("2D study: the closed form agrees with an independent quadrature to 1e-9") {
    for (auto conv : {GridConvention::NodeCentred, GridConvention::CellCentred}) {
        Study2D s;
        s.convention = conv;
        const Rays2D study(s);
        const auto rays = study.closedForm();
        REQUIRE(rays.size() == 120);
        int hits = 0;
        for (int i : {0, 6, 7, 30, 59, 60, 90, 104, 106, 110, 119}) {
            if (rays[i].length == 0.0) continue;
            ++hits;
            CHECK(rays[i].closedForm == doctest::Approx(quadrature(study, i, 200)).epsilon(0).scale(0).epsilon(1e-9));
        }
        CHECK(hits == 8);  // rays 6 to 106 hit the square
    }
}

TEST_CASE("2D study: ray angles are centred in equal sectors of the field of view") {
    Study2D s;
    CHECK(s.rayAngleDegrees(0) == doctest::Approx(-15.0 + 0.125));
    CHECK(s.rayAngleDegrees(119) == doctest::Approx(15.0 - 0.125));
    CHECK(s.rayAngleDegrees(60) - s.rayAngleDegrees(59) == doctest::Approx(0.25));
}

TEST_CASE("2D study: every placement converges to the closed form as the sampling rate grows") {
    for (auto conv : {GridConvention::NodeCentred, GridConvention::CellCentred}) {
        Study2D s;
        s.convention = conv;
        const Rays2D study(s);
        const auto exact = study.closedForm();
        for (auto p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign, Placement::EntryExitAlignCorner}) {
            double previous = 1e300;
            for (double rate : {1.0, 4.0, 16.0, 64.0}) {
                double maxError = 0.0;
                for (const auto& r : exact) maxError = std::max(maxError, std::abs(study.discrete(r.index, p, rate).intensity - r.closedForm));
                CHECK(maxError < previous);
                previous = maxError;
            }
            CHECK(previous < 0.03);
        }
    }
}

TEST_CASE("2D study: Fig. 2's features") {
    const Rays2D study{Study2D{}};
    const auto exact = study.closedForm();
    SUBCASE("entry-exit-corner gives every ray of positive length a sample, at every rate") {
        for (double rate : {1.0, 4.0, 16.0})
            for (const auto& r : exact)
                if (r.length > 0) CHECK(study.discrete(r.index, Placement::EntryExitAlignCorner, rate).samples >= 1);
    }
    SUBCASE("entry-exit drops to zero before the closed form does near a corner, corner align does not") {
        int dropped = 0;
        for (const auto& r : exact) {
            if (r.length <= 0) continue;
            if (study.discrete(r.index, Placement::EntryExitAlign, 1.0).intensity == 0.0) {
                ++dropped;
                CHECK(r.closedForm > 0.0);
                CHECK(study.discrete(r.index, Placement::EntryExitAlignCorner, 1.0).intensity > 0.0);
            }
        }
        CHECK(dropped >= 1);
    }
    SUBCASE("eye and entry align over- and underestimate: errors of both signs at rate 1") {
        for (auto p : {Placement::EyeAlign, Placement::EntryAlign}) {
            bool over = false, under = false;
            for (const auto& r : exact) {
                if (r.length <= 0) continue;
                const double e = study.discrete(r.index, p, 1.0).intensity - r.closedForm;
                over = over || e > 1e-3;
                under = under || e < -1e-3;
            }
            CHECK(over);
            CHECK(under);
        }
    }
}

namespace {

struct Segment {
    std::string panel, kind;
    double x, y, x2, y2;
    double length() const { return std::hypot(x2 - x, y2 - y); }
};

std::vector<Segment> parseDiagram(const std::string& csv) {
    std::vector<Segment> out;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);
    CHECK(line == "panel,kind,x,y,x2,y2");
    while (std::getline(in, line)) {
        std::istringstream row(line);
        Segment s;
        std::string cell;
        std::getline(row, s.panel, ',');
        std::getline(row, s.kind, ',');
        for (double* v : {&s.x, &s.y, &s.x2, &s.y2}) {
            std::getline(row, cell, ',');
            *v = std::stod(cell);
        }
        out.push_back(s);
    }
    return out;
}

double total(const std::vector<Segment>& segments, const std::string& panel, const std::string& kind) {
    double sum = 0.0;
    for (const Segment& s : segments)
        if (s.panel == panel && s.kind == kind) sum += s.length();
    return sum;
}

}  // namespace

TEST_CASE("2D study diagram: covered and missed stretches add up to the ray inside the square") {
    const Rays2D study{Study2D{}};
    const auto exact = study.closedForm();
    for (int ray : {20, 70, 105}) {
        const auto segments = parseDiagram(diagramCsv(study, {ray}, {Placement::EyeAlign, Placement::EntryExitAlign,
                                                                     Placement::EntryExitAlignCorner}, 1.0));
        for (const char* panel : {"eye", "entry-exit", "entry-exit-corner"}) {
            CAPTURE(ray);
            CAPTURE(panel);
            CHECK(total(segments, panel, "covered") + total(segments, panel, "missed") ==
                  doctest::Approx(exact[ray].length).epsilon(1e-12));
        }
        // Entry Exit Align's stretches tile the ray exactly: nothing overshot, nothing missed (when it samples at all).
        if (study.samples(ray, Placement::EntryExitAlign, 1.0).positions.size() > 0) {
            CHECK(total(segments, "entry-exit", "overshot") < 1e-12);
            CHECK(total(segments, "entry-exit", "missed") < 1e-12);
        }
    }
    // Ray 105 is a corner ray shorter than one step: Entry Exit Align misses all of it, the corner variant none.
    const auto corner = parseDiagram(diagramCsv(study, {105}, {Placement::EntryExitAlign, Placement::EntryExitAlignCorner}, 1.0));
    CHECK(total(corner, "entry-exit", "missed") == doctest::Approx(exact[105].length));
    CHECK(total(corner, "entry-exit-corner", "missed") < 1e-12);
    CHECK(total(corner, "setup", "fan") > 0.0);
}

TEST_CASE("2D study tables: one CSV column per placement and rate, errors over the rays that hit") {
    const Rays2D study{Study2D{}};
    const Fan fan = castFan(study, {Placement::EntryAlign, Placement::EntryExitAlignCorner}, {1.0, 4.0});
    const std::string csv = fanCsv(fan);
    CHECK(csv.substr(0, csv.find('\n')) ==
          "ray,angle_deg,length,closed_form,entry_r1,entry_r4,entry-exit-corner_r1,entry-exit-corner_r4,"
          "n_entry_r1,n_entry_r4,n_entry-exit-corner_r1,n_entry-exit-corner_r4");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 121);
    const Table t = fanErrorTable(fan);
    REQUIRE(t.rows.size() == 4);
    CHECK(t.rows[3] == "entry-exit-corner, 4");
    for (const auto& row : t.cells) {
        CHECK(*row[0] >= *row[1]);            // max >= mean
        CHECK(*row[0] == std::max(*row[2], *row[3]));
    }
    CHECK(*t.cells[2][4] == 0.0);  // corner align leaves no ray without a sample
    CHECK(*t.cells[1][0] < *t.cells[0][0]);  // entry align: rate 4 beats rate 1
}

TEST_CASE("2D study: the fan, the diagram and the field image are limited before any work") {
    vri::Study2D study;
    study.rays = 2000000000;
    CHECK_THROWS_WITH_AS(vri::Rays2D{study}, "2D study: the fan: needs 2000000000 rays, limit 1000000", vri::Error);
    const vri::Rays2D rays{vri::Study2D{}};
    CHECK_THROWS_WITH_AS(vri::castFan(rays, {vri::Placement::EntryAlign}, {1e12}), doctest::Contains("limit 1000000000"),
                         vri::Error);
    CHECK_THROWS_WITH_AS(vri::diagramCsv(rays, {0}, {vri::Placement::EntryAlign}, 1e6), doctest::Contains("limit 1000000"),
                         vri::Error);
    CHECK_THROWS_WITH_AS(vri::fieldCsv(rays, 2049), "field image of 2049x2049 points: needs 4198401 points (rows), limit 4194304",
                         vri::Error);
    CHECK(vri::fieldCsv(rays, 11).size() > 0);
}
