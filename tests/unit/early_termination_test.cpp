// Early ray termination with a bound (--early-termination auto): for every fixed-step integrator,
// precision and emission model the image stays within the stated bound of the image without
// termination, the stats' largest left-out amount lies below the bound and above what was really
// left out, the packet engine ends every ray where the scalar path does; the same for the Simpson
// methods, which refuse the bound where it would leave double's range.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

// A dense ball (s up to 1 in the middle) inside a thin shell of s = 0.3, in 26x22x20 voxels: rays through
// the middle become opaque, rays through the rim stay thin.
Scene ballScene(VoxelType type, EmissionModel emission) {
    auto v = std::make_shared<Volume>(glm::ivec3(26, 22, 20), type);
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 22; ++y)
            for (int x = 0; x < 26; ++x) {
                const double r = std::sqrt((x - 12.5) * (x - 12.5) + (y - 10.5) * (y - 10.5) + (z - 9.5) * (z - 9.5));
                const double s = r < 8.0 ? 1.0 - r / 10.0 : (r < 9.5 ? 0.3 : 0.0);
                const std::size_t i = v->index(x, y, z);
                if (type == VoxelType::UInt8) v->data<std::uint8_t>()[i] = static_cast<std::uint8_t>(s * 255.0);
                if (type == VoxelType::Float32) v->data<float>()[i] = static_cast<float>(s);
            }
    if (type == VoxelType::Float32) v->range = ValueRange{0.0, 1.0};
    // Colour up to 1.5 (so that the colour factor exceeds alpha's) and extinction up to 3 per voxel.
    const TransferFunction tf({{0.0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0}, {0.4, 0.8, 0.3, 0.2, 0.8}, {1.0, 1.5, 0.9, 0.4, 3.0}},
                              emission);
    return Scene{v, std::nullopt, GridConvention::CellCentred, tf};
}

Camera ballCamera() {
    const CameraSpec spec = test::cameraSpec(glm::dvec3(40.0, 30.0, -45.0), glm::dvec3(13.0, 11.0, 10.0), 35.0, 41, 33);
    return Camera(spec);
}

double largestDifference(const Image& a, const Image& b) {
    double d = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) d = std::max(d, std::abs(double(a.pixels[i]) - b.pixels[i]));
    return d;
}

}  // namespace

TEST_CASE("early termination auto: the image stays within the stated bound of the image without it") {
    const Camera camera = ballCamera();
    for (VoxelType type : {VoxelType::UInt8, VoxelType::Float32})
        for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour})
            for (Integrator integrator : {Integrator::Riemann, Integrator::Composite})
                for (Precision precision : {Precision::Double, Precision::Float})
                    for (double bound : {1e-2, 1e-3}) {
                        const Scene scene = ballScene(type, emission);
                        RenderOptions opt;
                        opt.integrator = integrator;
                        opt.precision = precision;
                        opt.samplingRate = 1.0 / 0.7;
                        RenderStats full, cut;
                        const Image all = render(scene, camera, opt, &full);
                        opt.terminationBound = bound;
                        const Image ended = render(scene, camera, opt, &cut);
                        INFO(voxelTypeName(type), " ", integratorName(integrator), " ", precisionName(precision),
                             " emission ", emissionModelName(emission), " bound ", bound);
                        // Float's own rounding of the sums: a few ulps of values below 2.
                        const double rounding = precision == Precision::Float ? 1e-6 : 1e-12;
                        const double difference = largestDifference(all, ended);
                        CHECK(full.raysTerminated == 0);
                        CHECK(cut.raysTerminated > 0);
                        CHECK(cut.samplesPlaced < full.samplesPlaced);
                        CHECK(cut.terminationLeftOut < bound);
                        CHECK(difference <= cut.terminationLeftOut + rounding);
                        // Not a blank test: something was left out.
                        CHECK(difference > 0.0);
                    }
}

TEST_CASE("early termination auto: the packet engine ends every ray at the scalar path's sample") {
    const Camera camera = ballCamera();
    for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour})
        for (Integrator integrator : {Integrator::Riemann, Integrator::Composite}) {
            const Scene scene = ballScene(VoxelType::UInt8, emission);
            RenderOptions opt;
            opt.integrator = integrator;
            opt.precision = Precision::Float;
            opt.terminationBound = 1e-3;
            RenderStats packetStats, scalarStats;
            const Image packets = render(scene, camera, opt, &packetStats);
            opt.simd = false;
            const Image scalar = render(scene, camera, opt, &scalarStats);
            CHECK(!packetStats.simdTarget.empty());
            CHECK(std::memcmp(packets.pixels.data(), scalar.pixels.data(), scalar.pixels.size() * sizeof(float)) == 0);
            CHECK(packetStats.samplesPlaced == scalarStats.samplesPlaced);
            CHECK(packetStats.raysTerminated == scalarStats.raysTerminated);
            CHECK(packetStats.terminationLeftOut == scalarStats.terminationLeftOut);
            CHECK(scalarStats.raysTerminated > 0);
        }
}

TEST_CASE("early termination auto: the Simpson methods stay within the stated bound of the image without it") {
    // The ball's rim at an extinction of 3 per voxel brings the transparency near the thresholds, then a
    // wall of 40 per voxel (s >= 0.5, within 5 voxels of the middle): Simpson steps of up to 3 voxels
    // cross it at optical depths up to 120 a step, where the quadrature adds several times what the
    // integral of the rest (C_max T) allows; the rule's factor covers what the quadrature adds
    // (early_termination.h).
    const Camera camera = ballCamera();
    const auto wallScene = [](EmissionModel emission) {
        Scene scene = ballScene(VoxelType::UInt8, emission);
        scene.transferFunction = TransferFunction(
            {{0.0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0}, {0.15, 0.8, 0.3, 0.2, 3}, {0.45, 0.8, 0.3, 0.2, 3}, {0.5, 1.5, 0.9, 0.4, 40},
             {1.0, 1.5, 0.9, 0.4, 40}},
            emission);
        return scene;
    };
    struct Case {
        Integrator integrator;
        double step, hMax;
        AcceptedValue accepted;
    };
    const double none = std::numeric_limits<double>::infinity();
    const Case cases[] = {{Integrator::Simpson, 0.7, 0.7, AcceptedValue::Richardson},
                          {Integrator::Simpson, 3.0, 3.0, AcceptedValue::Richardson},
                          {Integrator::Coupled, 1.0, 3.0, AcceptedValue::Richardson},
                          {Integrator::Coupled, 1.0, 3.0, AcceptedValue::PaperDPlusE},
                          {Integrator::Decoupled, 1.0, 3.0, AcceptedValue::Richardson},
                          {Integrator::Decoupled, 1.0, 3.0, AcceptedValue::PaperDPlusE},
                          {Integrator::Decoupled, 1.0, none, AcceptedValue::Richardson}};
    for (const Case& c : cases)
        for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour})
            for (Precision precision : {Precision::Double, Precision::Float})
                for (double bound : {1e-2, 1e-4, 1e-6}) {
                    const Scene scene = wallScene(emission);
                    RenderOptions opt;
                    opt.integrator = c.integrator;
                    opt.precision = precision;
                    opt.samplingRate = 1.0 / c.step;
                    opt.adaptive.h0 = c.step;
                    opt.adaptive.hMin = 0.1;
                    opt.adaptive.hMax = c.hMax;
                    opt.adaptive.accepted = c.accepted;
                    RenderStats full, cut;
                    const Image all = render(scene, camera, opt, &full);
                    opt.terminationBound = bound;
                    const Image ended = render(scene, camera, opt, &cut);
                    INFO(integratorName(c.integrator), " step ", c.step, " h_max ", c.hMax, " ",
                         acceptedValueName(c.accepted), " ", precisionName(precision), " emission ",
                         emissionModelName(emission), " bound ", bound);
                    const double rounding = precision == Precision::Float ? 1e-6 : 1e-12;
                    CHECK(full.raysTerminated == 0);
                    CHECK(cut.raysTerminated > 0);
                    CHECK(cut.terminationLeftOut < bound);
                    CHECK(largestDifference(all, ended) <= cut.terminationLeftOut + rounding);
                }
}

TEST_CASE("early termination auto: refused where the Simpson methods' rest has no bound in range") {
    // Extinction 1e3 per voxel and no h_max: a step may cross the whole ray at an optical depth of 4e4,
    // whose exp(depth / 48) leaves double's range.
    Scene scene = ballScene(VoxelType::UInt8, EmissionModel::ColourTimesExtinction);
    scene.transferFunction = TransferFunction({{0.0, 0, 0, 0, 0}, {0.1, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1e3}},
                                              EmissionModel::ColourTimesExtinction);
    RenderOptions opt;
    opt.integrator = Integrator::Decoupled;
    opt.adaptive.hMax = std::numeric_limits<double>::infinity();
    opt.terminationBound = 1e-3;
    CHECK_THROWS_WITH_AS(render(scene, ballCamera(), opt),
                         doctest::Contains("--early-termination auto:0.001: decoupled with steps up to the whole ray"),
                         Error);
    opt.adaptive.hMax = 2.0;  // a step's depth of at most 2e3: K = exp(2e3 / 48) 2e3 is in range
    RenderStats stats;
    render(scene, ballCamera(), opt, &stats);
    CHECK(stats.raysTerminated > 0);
}

TEST_CASE("early termination: off changes nothing, and the explicit threshold reports what it left out") {
    const Scene scene = ballScene(VoxelType::UInt8, EmissionModel::ColourTimesExtinction);
    const Camera camera = ballCamera();
    RenderOptions opt;
    RenderStats stats;
    render(scene, camera, opt, &stats);
    CHECK(stats.raysTerminated == 0);
    CHECK(stats.terminationLeftOut == 0.0);
    opt.earlyTermination = 0.05;
    const Image all = render(scene, camera, RenderOptions{}), ended = render(scene, camera, opt, &stats);
    CHECK(stats.raysTerminated > 0);
    CHECK(stats.terminationLeftOut > 0.05);  // colour up to 1.5: the factor exceeds 1
    CHECK(largestDifference(all, ended) <= stats.terminationLeftOut + 1e-12);
    opt.terminationBound = 1e-3;
    CHECK_THROWS_AS(render(scene, camera, opt), Error);  // a threshold and a bound
}

TEST_CASE("parseEarlyTermination takes a transparency, auto and auto:BOUND") {
    RenderOptions o;
    parseEarlyTermination("0.25", "--early-termination", o);
    CHECK(o.earlyTermination == 0.25);
    CHECK(o.terminationBound == 0.0);
    parseEarlyTermination("auto", "--early-termination", o);
    CHECK(o.earlyTermination == 0.0);
    CHECK(o.terminationBound == kAutoTerminationBound);
    parseEarlyTermination("auto:1e-6", "--early-termination", o);
    CHECK(o.terminationBound == 1e-6);
    parseEarlyTermination("0", "--early-termination", o);
    CHECK(o.terminationBound == 0.0);
    CHECK(o.earlyTermination == 0.0);
    for (const char* bad : {"1", "-0.1", "auto:0", "auto:1", "auto:", "autox", "nan", ""})
        CHECK_THROWS_AS(parseEarlyTermination(bad, "--early-termination", o), Error);
}
