// The tau h limit of simpson_range.h, measured on the integrator itself: one uniform Simpson step from
// full transparency, its five extinctions searched over [0, kappa_max], gives no alpha above 1 at the
// limit and one above 1 a little beyond it; and a render counts the rays whose steps went beyond.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "test_camera.h"
#include "libvri/core/adaptive_simpson.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/simpson_range.h"

using namespace vri;

namespace {

using Profile = std::array<double, 5>;  // kappa at v = 0, 1/4, 1/2, 3/4, 1, in units of kappa_max

// Alpha of one step of h = 1 voxel from full transparency, kappa_max = x, the step's five points
// taking the profile's values.
double stepAlpha(const Profile& k, double x, AcceptedValue accepted) {
    AdaptiveParameters p;
    p.coupling = Coupling::Coupled;
    p.h0 = p.hMin = p.hMax = 1.0;
    p.accepted = accepted;
    AdaptiveCounts counts;
    const auto result = AdaptiveSimpsonRay<double>(p).integrate(
        1.0, [&](double v) { return RayPoint<double>{x * k[static_cast<std::size_t>(v * 4.0)], 0, 0, 0}; },
        [](double, double) { return false; }, counts);
    return result.alpha;
}

// The largest step alpha over the profiles: every value on a grid of ninths, then a coordinate search
// from the best of them in steps halving down to 1e-4.
double largestStepAlpha(double x, AcceptedValue accepted) {
    Profile best{}, k{};
    double largest = 0.0;
    for (int i = 0; i < 100000; ++i) {
        int code = i;
        for (double& v : k) v = (code % 10) / 9.0, code /= 10;
        if (const double a = stepAlpha(k, x, accepted); a > largest) largest = a, best = k;
    }
    for (double delta = 0.05; delta > 1e-4; delta /= 2)
        for (bool improved = true; improved;) {
            improved = false;
            for (std::size_t j = 0; j < 5; ++j)
                for (const double sign : {-1.0, 1.0}) {
                    Profile next = best;
                    next[j] = std::clamp(next[j] + sign * delta, 0.0, 1.0);
                    if (const double a = stepAlpha(next, x, accepted); a > largest)
                        largest = a, best = next, improved = true;
                }
        }
    return largest;
}

}  // namespace

TEST_CASE("Simpson range: one step's alpha stays within 1 up to the limit and leaves it beyond") {
    for (const AcceptedValue accepted : {AcceptedValue::Richardson, AcceptedValue::PaperDPlusE}) {
        INFO(acceptedValueName(accepted));
        const double limit = simpsonStepDepthLimit(accepted);
        CHECK(largestStepAlpha(limit, accepted) <= 1.0);
        CHECK(largestStepAlpha(limit + 0.02, accepted) > 1.0);
        // Constant extinction: Richardson's is Boole's rule on exp(-x v), within 1 further (to 5.25); the steep rise
        // far beyond grows as exp(x / 48): not a quadrature error but the quarter points' extrapolated
        // transparency.
        const double x = limit + 0.02;
        const double boole = x / 180 * (14 + 64 * std::exp(-x / 4) + 24 * std::exp(-x / 2) + 64 * std::exp(-3 * x / 4) +
                                         14 * std::exp(-x));
        if (accepted == AcceptedValue::Richardson)
            CHECK(stepAlpha({1, 1, 1, 1, 1}, x, accepted) == doctest::Approx(boole).epsilon(1e-14));
        CHECK(boole <= 1.0);
        CHECK(stepAlpha({1, 1, 1, 1, 1}, x, accepted) <= 1.0);
        CHECK(largestStepAlpha(480.0, accepted) > 1e4);
    }
}

TEST_CASE("Simpson range: a render counts the rays whose steps went beyond the limit") {
    // A ramp of 8^3 voxels under an extinction of 0.5 and then of 50 per voxel, uniform Simpson at h = 1.
    auto v = std::make_shared<Volume>(glm::ivec3(8, 8, 8), VoxelType::UInt8);
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) v->data<std::uint8_t>()[v->index(x, y, z)] = static_cast<std::uint8_t>(x * 36);
    const Camera camera(test::cameraSpec(glm::dvec3(4.0, 4.0, -20.0), glm::dvec3(4.0, 4.0, 4.0), 30.0, 16, 12));
    RenderOptions opt;
    opt.integrator = Integrator::Simpson;
    opt.samplingRate = 1.0;
    for (const double tau : {0.5, 50.0}) {
        const Scene scene{v, std::nullopt, GridConvention::CellCentred,
                          TransferFunction({{0.0, 0, 0, 0, 0}, {0.3, 1, 1, 1, tau}, {1.0, 1, 1, 1, tau}},
                                           EmissionModel::ColourTimesExtinction)};
        RenderStats stats;
        render(scene, camera, opt, &stats);
        REQUIRE(stats.simpsonRange);
        CHECK(stats.simpsonRange->limit == simpsonStepDepthLimit(AcceptedValue::Richardson));
        CHECK(stats.simpsonRange->largest <= tau * 1.0 + 1e-12);  // tau h, h = 1 voxel of unit spacing
        if (tau < stats.simpsonRange->limit) {
            CHECK(stats.simpsonRange->pixelsBeyond == 0);
        } else {
            CHECK(stats.simpsonRange->largest > stats.simpsonRange->limit);
            CHECK(stats.simpsonRange->pixelsBeyond > 0);
            CHECK(stats.simpsonRange->pixelsBeyond <= stats.raysHit);
        }
    }
    opt.integrator = Integrator::Riemann;  // the fixed-step methods have no such range
    RenderStats stats;
    render(Scene{v, std::nullopt, GridConvention::CellCentred, TransferFunction({{0.0, 0, 0, 0, 1}, {1.0, 1, 1, 1, 1}}, EmissionModel::ColourTimesExtinction)},
           camera, opt, &stats);
    CHECK(!stats.simpsonRange);
}
