// The CPU raycaster against paper A's closed form, and its bitwise determinism.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <tbb/global_control.h>

#include "libvri/core/cpu_renderer.h"

using namespace vri;
using V = glm::dvec3;

namespace {

TransferFunction paperATransferFunction() {  // g(s) = s, tau(s) = s / 2
    return TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, 0.5}}, EmissionModel::Colour);
}

// One ray along +x through the centre of paper A's cube: f rises from 0 to 1 over D = 3, so
// F(D) = 1.5 and I = 2 (1 - exp(-F / 2)).
double centreRay(const Scene& scene, Placement placement, double rate, Integrator integrator = Integrator::Riemann) {
    CameraSpec spec;
    spec.eye = V(-9.0, 0.0, 0.0);
    spec.target = V(0.0);
    spec.width = spec.height = 1;
    RenderOptions opt;
    opt.placement = placement;
    opt.samplingRate = rate;
    opt.integrator = integrator;
    return render(scene, Camera(spec), opt).at(0, 0, 0);
}

Scene analyticScene() { return Scene{nullptr, LinearField{}, GridConvention::NodeCentred, paperATransferFunction()}; }

}  // namespace

TEST_CASE("Riemann on the linear field converges linearly to the closed form") {
    const double exact = 2.0 * (1.0 - std::exp(-0.75));
    const Scene scene = analyticScene();
    double previous = 0.0;
    for (double rate : {2.0, 4.0, 8.0, 16.0, 32.0}) {
        const double error = std::abs(centreRay(scene, Placement::EntryExitAlign, rate) - exact);
        CHECK(error < 0.1);
        if (previous > 0.0) {
            const double order = std::log2(previous / error);
            CHECK(order == doctest::Approx(1.0).epsilon(0.15));  // first order: the inner sum lags half a step
        }
        previous = error;
    }
}

TEST_CASE("the same field sampled onto a node grid renders like the analytic field") {
    const Scene analytic = analyticScene();
    auto grid = std::make_shared<Volume>(sampleOntoGrid(LinearField{}, GridConvention::NodeCentred));
    const Scene sampled{grid, std::nullopt, GridConvention::NodeCentred, paperATransferFunction()};
    for (auto p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                   Placement::EntryExitAlignCorner})
        CHECK(centreRay(sampled, p, 4.0) == doctest::Approx(centreRay(analytic, p, 4.0)).epsilon(1e-6));
}

TEST_CASE("composite (opacity-corrected) is exact for a constant field") {
    // g = 0.5, tau = 0.25 everywhere: I = g / tau (1 - exp(-tau D)) with D = 3.
    const TransferFunction tf({{0, 0.5, 0.5, 0.5, 0.25}, {1, 0.5, 0.5, 0.5, 0.25}}, EmissionModel::Colour);
    const Scene scene{nullptr, LinearField{}, GridConvention::NodeCentred, tf};
    const double exact = 0.5 / 0.25 * (1.0 - std::exp(-0.75));
    CHECK(centreRay(scene, Placement::EntryExitAlign, 1.0, Integrator::Composite) == doctest::Approx(exact).epsilon(1e-7));
}

namespace {

std::shared_ptr<Volume> noisyBlob(int n) {
    auto v = std::make_shared<Volume>(glm::ivec3(n), VoxelType::UInt8);
    std::mt19937 rng(11);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const V p = (V(x, y, z) + 0.5) / double(n) - 0.5;
                const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
                const int base = r < 0.3 ? 200 - int(400 * r) : 0;  // empty space around a blob
                v->data<std::uint8_t>()[v->index(x, y, z)] = static_cast<std::uint8_t>(base ? base + int(rng() % 20) : 0);
            }
    return v;
}

Image renderBlob(const Scene& scene, RenderOptions opt, RenderStats* stats = nullptr) {
    const Camera camera(framingCamera(scene.box(), 48, 40, 30.0));
    return render(scene, camera, opt, stats);
}

bool bitwiseEqual(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("images are bitwise identical across thread counts and with empty-space skipping off") {
    const TransferFunction tf({{0, 0, 0, 0, 0}, {0.3, 0, 0, 0, 0}, {0.6, 1, 0.5, 0.2, 0.3}, {1, 1, 1, 1, 1}},
                              EmissionModel::ColourTimesExtinction);
    for (auto conv : {GridConvention::CellCentred, GridConvention::NodeCentred})
        for (auto precision : {Precision::Double, Precision::Float})
            for (auto placement : {Placement::EyeAlign, Placement::EntryExitAlignCorner}) {
                const Scene scene{noisyBlob(32), std::nullopt, conv, tf};
                RenderOptions opt;
                opt.precision = precision;
                opt.placement = placement;
                opt.samplingRate = 3.0;
                RenderStats skipped;
                const Image reference = renderBlob(scene, opt, &skipped);
                Image single;
                {
                    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                    single = renderBlob(scene, opt);
                }
                CHECK(bitwiseEqual(reference, single));
                opt.skipEmptySpace = false;
                RenderStats full;
                CHECK(bitwiseEqual(reference, renderBlob(scene, opt, &full)));
                CHECK(skipped.samplesEvaluated < full.samplesEvaluated);  // and skipping did skip
                CHECK(skipped.samplesPlaced == full.samplesPlaced);
            }
}

TEST_CASE("float and double renders agree to float precision") {
    const TransferFunction tf({{0, 0, 0, 0, 0}, {0.3, 0, 0, 0, 0}, {1, 1, 1, 1, 0.5}}, EmissionModel::ColourTimesExtinction);
    const Scene scene{noisyBlob(24), std::nullopt, GridConvention::CellCentred, tf};
    RenderOptions opt;
    const Image d = renderBlob(scene, opt);
    opt.precision = Precision::Float;
    const Image f = renderBlob(scene, opt);
    double maxDiff = 0;
    for (std::size_t i = 0; i < d.pixels.size(); ++i) maxDiff = std::max(maxDiff, double(std::abs(d.pixels[i] - f.pixels[i])));
    CHECK(maxDiff < 1e-4);
}

TEST_CASE("render rejects a non-positive step") {
    RenderOptions opt;
    opt.samplingRate = 0.0;
    CHECK_THROWS_AS(renderBlob(analyticScene(), opt), std::exception);
    opt.samplingRate = -1.0;
    CHECK_THROWS_AS(renderBlob(analyticScene(), opt), std::exception);
}

TEST_CASE("skipping stays bitwise neutral in float with a narrow range far from zero") {
    // Every voxel 1001 with range [1000.1, 1001.1]: s = 0.9 in double, a little more in float, right
    // where the transfer function starts to rise. The brick test must not call it empty.
    auto v = std::make_shared<Volume>(glm::ivec3(16), VoxelType::UInt16);
    for (std::size_t i = 0; i < v->voxelCount(); ++i) v->data<std::uint16_t>()[i] = 1001;
    v->range = ValueRange{1000.1, 1001.1};
    const TransferFunction tf({{0, 0, 0, 0, 0}, {0.90001, 0, 0, 0, 0}, {1, 1, 1, 1, 10}}, EmissionModel::ColourTimesExtinction);
    const Scene scene{v, std::nullopt, GridConvention::CellCentred, tf};
    for (auto precision : {Precision::Double, Precision::Float}) {
        RenderOptions opt;
        opt.precision = precision;
        const Image skipped = renderBlob(scene, opt);
        opt.skipEmptySpace = false;
        CHECK(bitwiseEqual(skipped, renderBlob(scene, opt)));
    }
}

TEST_CASE("render rejects settings it cannot honour") {
    RenderOptions opt;
    opt.samplingRate = 1e300;
    CHECK_THROWS_WITH_AS(renderBlob(analyticScene(), opt), doctest::Contains("1e9 samples"), std::exception);
    opt.samplingRate = 2.0;
    // The Simpson methods' budget: h_min bounds the steps of a ray whatever the tolerance; in float
    // a step below 2^-22 of the ray no longer advances it.
    opt.integrator = Integrator::Coupled;
    opt.adaptive.tolerance = 0.0;
    opt.adaptive.hMin = 1e-300;
    CHECK_THROWS_WITH_AS(renderBlob(analyticScene(), opt), doctest::Contains("h_min 1e-300 would allow more than 1e9"),
                         std::exception);
    opt.adaptive.hMin = 1e-7;
    opt.precision = Precision::Float;
    CHECK_THROWS_WITH_AS(renderBlob(analyticScene(), opt), doctest::Contains("2^22 steps"), std::exception);
    opt.integrator = Integrator::Simpson;
    opt.samplingRate = 1e7;
    CHECK_THROWS_WITH_AS(renderBlob(analyticScene(), opt), doctest::Contains("step 1e-07 would allow"), std::exception);
    opt = RenderOptions{};
    opt.earlyTermination = -0.5;
    CHECK_THROWS_AS(renderBlob(analyticScene(), opt), std::exception);
    auto flat = std::make_shared<Volume>(glm::ivec3(16, 16, 1), VoxelType::UInt8);
    const Scene scene{flat, std::nullopt, GridConvention::NodeCentred, paperATransferFunction()};
    CHECK_THROWS_WITH_AS(render(scene, Camera(CameraSpec{}), RenderOptions{}), doctest::Contains("node-centred"),
                         std::exception);
}
