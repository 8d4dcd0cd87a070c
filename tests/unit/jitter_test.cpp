// Jittered sampling: the per-pixel fraction (reproducible, uniform, seed-dependent), the schedule it
// moves, and jittered renders: bitwise the same per seed across tilings and thread counts, different
// across seeds, and --frames the mean of consecutive seeds.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <memory>

#include <tbb/global_control.h>

#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/jitter.h"

using namespace vri;

TEST_CASE("jitter: the fraction is a reproducible multiple of 2^-24 from 0 up to 1, uniform, different per seed") {
    constexpr int n = 256;
    double sum = 0.0;
    std::array<int, 16> bins{};
    int differ = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double f = jitterFraction(x, y, 7);
            CHECK_MESSAGE(f == jitterFraction(x, y, 7), "pixel ", x, ",", y);
            REQUIRE(f >= 0.0);
            REQUIRE(f < 1.0);
            REQUIRE(std::ldexp(f, 24) == std::floor(std::ldexp(f, 24)));
            REQUIRE(static_cast<double>(static_cast<float>(f)) == f);
            sum += f;
            ++bins[static_cast<int>(f * 16)];
            differ += f != jitterFraction(x, y, 8);
        }
    // Mean offset h/2: the mean fraction over 65536 pixels is 1/2 within a few standard errors (1/sqrt(12 n^2)).
    CHECK(std::abs(sum / (n * n) - 0.5) < 0.005);
    for (const int b : bins) CHECK(std::abs(b - n * n / 16) < n * n / 160);  // each sixteenth within 10 %
    CHECK(differ > n * n * 99 / 100);
    CHECK(jitterFraction(0, 0, 0) != jitterFraction(1, 0, 0));
    CHECK(jitterFraction(0, 1, 0) != jitterFraction(1, 0, 0));
}

TEST_CASE("jitter: the first sample moves to the fraction of the step, the step and the end kept") {
    SampleSchedule<double> s = placeSamples<double>(Placement::EntryAlign, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0},
                                                    {-1.0, 0.0, 0.0}, {10.0, 10.0, 10.0}, 2.0);
    REQUIRE(s.count == 20);
    const double step = s.tIncr;
    jitterSchedule(s, 0.0);
    CHECK(s.tStart == 0.0);
    CHECK(s.tIncr == step);
    CHECK(s.count == 20);  // t = 0, ..., 19 step < 1
    jitterSchedule(s, 0.75);
    CHECK(s.tStart == 0.75 * step);
    CHECK(s.count == 20);
    CHECK(s.t(s.count - 1) < s.tEnd);
    CHECK(!(s.t(s.count) < s.tEnd));
}

namespace {

Scene jitterScene() {
    // The linear field under a transfer function with a sharp rise: where the samples' phase shows.
    return Scene{nullptr, LinearField{}, GridConvention::CellCentred,
                 TransferFunction({{0.0, 0.0, 0.0, 0.0, 0.0}, {0.4, 0.0, 0.0, 0.0, 0.0}, {0.45, 1.0, 0.6, 0.2, 4.0},
                                   {1.0, 0.2, 0.6, 1.0, 1.0}},
                                  EmissionModel::ColourTimesExtinction)};
}

}  // namespace

TEST_CASE("jitter: renders are bitwise reproducible per seed, across tiles and threads, and differ across seeds") {
    const Camera camera(test::cameraSpec({-4.0, 1.5, 2.5}, {0.1, -0.2, 0.0}, 40.0, 20, 14));
    const Scene scene = jitterScene();
    for (const Integrator method : {Integrator::Riemann, Integrator::Composite, Integrator::Preintegrated})
        for (const Precision precision : {Precision::Double, Precision::Float}) {
            RenderOptions opt;
            opt.integrator = method;
            opt.precision = precision;
            opt.preintegrationSize = 32;
            opt.jitter = true;
            opt.seed = 3;
            const Image a = render(scene, camera, opt);
            opt.tileSize = 5;
            Image b;
            {
                tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                b = render(scene, camera, opt);
            }
            CHECK(a.pixels == b.pixels);
            opt.seed = 4;
            const Image c = render(scene, camera, opt);
            CHECK(a.pixels != c.pixels);
            opt.jitter = false;
            const Image plain = render(scene, camera, opt);
            CHECK(a.pixels != plain.pixels);
        }
}

TEST_CASE("jitter: --frames N is the mean of seeds seed .. seed + N - 1, summed in double") {
    const Camera camera(test::cameraSpec({-4.0, 1.5, 2.5}, {0.1, -0.2, 0.0}, 40.0, 12, 10));
    const Scene scene = jitterScene();
    RenderOptions opt;
    opt.precision = Precision::Float;
    opt.jitter = true;
    opt.seed = 10;
    opt.frames = 3;
    RenderStats stats;
    const Image mean = render(scene, camera, opt, &stats);
    opt.frames = 1;
    std::vector<double> sum(mean.pixels.size(), 0.0);
    std::uint64_t samples = 0;
    for (std::uint32_t seed = 10; seed < 13; ++seed) {
        opt.seed = seed;
        RenderStats one;
        const Image frame = render(scene, camera, opt, &one);
        samples += one.samplesPlaced;
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += frame.pixels[i];
    }
    for (std::size_t i = 0; i < sum.size(); ++i) REQUIRE(mean.pixels[i] == static_cast<float>(sum[i] / 3.0));
    CHECK(stats.samplesPlaced == samples);
}

TEST_CASE("jitter: refused where it has no meaning") {
    const Camera camera(test::cameraSpec({-4.0, 1.5, 2.5}, {0.1, -0.2, 0.0}, 40.0, 4, 4));
    RenderOptions opt;
    opt.integrator = Integrator::Simpson;
    opt.jitter = true;
    CHECK_THROWS_WITH(render(jitterScene(), camera, opt),
                      "jitter: applies to the placed fixed-step methods (riemann, composite, preintegrated), not simpson");
    opt.integrator = Integrator::Riemann;
    opt.jitter = false;
    opt.frames = 2;
    CHECK_THROWS_WITH(render(jitterScene(), camera, opt), "frames: averaging frames needs jitter (each frame a seed)");
}
