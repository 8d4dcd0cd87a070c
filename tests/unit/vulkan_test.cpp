// The Vulkan backend against the CPU raycaster in float, on whatever Vulkan device comes first
// (Mesa's lavapipe on a machine without a GPU). Skipped when there is no Vulkan device at all.
//
// Tolerances. The two backends integrate the same clipped rays at the same sample positions with
// the same float formulas; what may differ is the rounding of exp(), of division and of sqrt(),
// which Vulkan lets a device compute to within a few ulp instead of correctly rounded. One ulp of
// relative error per sample, carried through a product of up to ~100 attenuations and a sum of as
// many terms, stays below 1e-5 of values that are at most a few units here: kFixedStep = 2e-5.
// The adaptive methods branch on float error estimates, so a tie broken differently takes other
// steps on that ray; both images then still approximate the integral within the tolerance, so their
// difference is bounded by a few times the tolerance the methods were run with (kAdaptive).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>

#include "libvri/core/cpu_renderer.h"
#include "libvri/core/image_compare.h"
#include "libvri/util/error.h"
#include "libvri/vulkan/vulkan_renderer.h"

using namespace vri;

namespace {

constexpr double kFixedStep = 2e-5;

bool haveVulkan() {
    if (!VulkanRenderer::listDevices().empty()) return true;
    MESSAGE("no Vulkan device: skipping");
    return false;
}

double maxDifference(const Image& a, const Image& b) {
    REQUIRE(a.pixels.size() == b.pixels.size());
    double d = 0;
    for (const auto& channel : compareImages(a, b, {}).channels) d = std::max(d, channel.maxAbs);
    return d;
}

// Voxel i of a volume of any type holds `value`.
void setVoxel(Volume& v, std::size_t i, int value) {
    dispatchVoxelType(v.type, [&](auto voxel) { v.data<decltype(voxel)>()[i] = static_cast<decltype(voxel)>(value); });
}

double maxValue(const Image& a) {
    double m = 0;
    for (float v : a.pixels) m = std::max(m, double(v));
    return m;
}

Scene linearScene() {  // paper A's field and transfer function: g(s) = s, tau(s) = s / 2
    return Scene{nullptr, LinearField{}, GridConvention::NodeCentred,
                 TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, 0.5}}, EmissionModel::Colour)};
}

// A noisy uint8 blob in empty space, converted to `type` (same values) when asked.
Scene blobScene(VoxelType type = VoxelType::UInt8) {
    const int n = 20;
    auto v = std::make_shared<Volume>(glm::ivec3(n, n - 3, n + 2), type);
    std::mt19937 rng(5);
    for (int z = 0; z < v->dims.z; ++z)
        for (int y = 0; y < v->dims.y; ++y)
            for (int x = 0; x < v->dims.x; ++x) {
                const glm::dvec3 p = (glm::dvec3(x, y, z) + 0.5) / glm::dvec3(v->dims) - 0.5;
                const double r = glm::length(p);
                const int base = r < 0.35 ? 220 - int(400 * r) : 0;
                setVoxel(*v, v->index(x, y, z), base > 0 ? base + int(rng() % 30) : 0);
            }
    v->range = ValueRange{0.0, 255.0};
    v->spacing = glm::dvec3(1.0, 1.25, 0.8);
    const TransferFunction tf({{0, 0, 0, 0, 0}, {0.25, 0, 0, 0, 0}, {0.5, 1, 0.5, 0.2, 0.3}, {0.5, 0.2, 0.8, 1, 0.6},
                               {1, 1, 1, 1, 1.2}},
                              EmissionModel::ColourTimesExtinction);
    return Scene{v, std::nullopt, GridConvention::CellCentred, tf};
}

// An oblique view, so that rays enter through different faces and the placements differ per pixel.
Camera obliqueCamera(const Scene& scene) {
    CameraSpec spec = framingCamera(scene.box(), 40, 30, 35.0);
    const glm::dvec3 c = scene.box().centre();
    spec.eye = c + glm::length(spec.eye - c) * glm::normalize(glm::dvec3(0.5, 0.4, 1.0));
    return Camera(spec);
}

RenderOptions floatOptions(Integrator integrator) {
    RenderOptions opt;
    opt.integrator = integrator;
    opt.precision = Precision::Float;
    opt.samplingRate = 3.0;
    return opt;
}

}  // namespace

TEST_CASE("Vulkan Riemann matches the CPU in float for every placement") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    for (const Scene& scene : {linearScene(), blobScene()}) {
        const Camera camera = obliqueCamera(scene);
        for (auto placement : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                               Placement::EntryExitAlignCorner}) {
            CAPTURE(placementName(placement));
            RenderOptions opt = floatOptions(Integrator::Riemann);
            opt.placement = placement;
            RenderStats cpuStats, gpuStats;
            opt.skipEmptySpace = false;  // as the GPU: then the sample counts agree too
            const Image cpu = render(scene, camera, opt, &cpuStats);
            const Image vk = gpu.render(scene, camera, opt, &gpuStats);
            const double d = maxDifference(cpu, vk);
            MESSAGE(placementName(placement), ": max difference ", d, " of values up to ", maxValue(cpu));
            CHECK(maxValue(cpu) > 0.1);
            CHECK(d <= kFixedStep);
            CHECK(gpuStats.raysHit == cpuStats.raysHit);
            CHECK(gpuStats.samplesPlaced == cpuStats.samplesPlaced);
            CHECK(gpuStats.backend == "vulkan");
            CHECK(gpuStats.device == gpu.device().name);
        }
    }
}

TEST_CASE("Vulkan empty-space skipping changes no bit of the image") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    const Scene scene = blobScene();
    const Camera camera = obliqueCamera(scene);
    for (auto [integrator, placement] : {std::pair{Integrator::Riemann, Placement::EyeAlign},
                                         std::pair{Integrator::Riemann, Placement::EntryExitAlignCorner},
                                         std::pair{Integrator::Coupled, Placement::EntryAlign},
                                         std::pair{Integrator::Decoupled, Placement::EntryAlign}}) {
        CAPTURE(integratorName(integrator));
        RenderOptions opt = floatOptions(integrator);
        opt.placement = placement;
        opt.skipEmptySpace = false;
        RenderStats full, skipping;
        const Image a = gpu.render(scene, camera, opt, &full);
        opt.skipEmptySpace = true;
        const Image b = gpu.render(scene, camera, opt, &skipping);
        CHECK(a.pixels == b.pixels);
        CHECK(skipping.samplesPlaced == full.samplesPlaced);
        CHECK(skipping.samplesEvaluated < full.samplesEvaluated);
    }
}

TEST_CASE("Vulkan reads uint16 and float32 volumes like uint8 ones") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    const RenderOptions opt = floatOptions(Integrator::Riemann);
    const Scene byteScene = blobScene();
    const Image reference = render(byteScene, obliqueCamera(byteScene), opt);
    for (auto type : {VoxelType::UInt16, VoxelType::Float32}) {
        CAPTURE(voxelTypeName(type));
        const Scene scene = blobScene(type);
        CHECK(maxDifference(reference, gpu.render(scene, obliqueCamera(scene), opt)) <= kFixedStep);
    }
}

TEST_CASE("Vulkan composite and uniform Simpson match the CPU in float") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    for (const Scene& scene : {linearScene(), blobScene()})
        for (auto integrator : {Integrator::Composite, Integrator::Simpson}) {
            CAPTURE(integratorName(integrator));
            const RenderOptions opt = floatOptions(integrator);
            const Camera camera = obliqueCamera(scene);
            const double d = maxDifference(render(scene, camera, opt), gpu.render(scene, camera, opt));
            MESSAGE(integratorName(integrator), ": max difference ", d);
            CHECK(d <= kFixedStep);
        }
}

TEST_CASE("Vulkan coupled and decoupled stay within a bound of the CPU in float") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    for (const Scene& scene : {linearScene(), blobScene()})
        for (auto integrator : {Integrator::Coupled, Integrator::Decoupled})
            for (double tolerance : {1e-2, 1e-4}) {
                CAPTURE(integratorName(integrator));
                CAPTURE(tolerance);
                RenderOptions opt = floatOptions(integrator);
                opt.adaptive.tolerance = tolerance;
                const Camera camera = obliqueCamera(scene);
                RenderStats cpuStats, gpuStats;
                opt.skipEmptySpace = false;
                const Image cpu = render(scene, camera, opt, &cpuStats);
                const Image vk = gpu.render(scene, camera, opt, &gpuStats);
                const double d = maxDifference(cpu, vk);
                MESSAGE(integratorName(integrator), " eps ", tolerance, ": max difference ", d, ", steps ",
                        gpuStats.adaptive->outerSteps, " (CPU ", cpuStats.adaptive->outerSteps, ")");
                CHECK(d <= std::max(kFixedStep, 4 * tolerance));
                REQUIRE(gpuStats.adaptive);
                const double steps = double(cpuStats.adaptive->outerSteps);
                CHECK(std::abs(double(gpuStats.adaptive->outerSteps) - steps) <= 0.01 * steps);
            }
}

TEST_CASE("Vulkan keeps the empty-space bricks across frames and replaces them when the scene changes") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    const Scene scene = blobScene();
    const Camera camera = obliqueCamera(scene);
    const RenderOptions opt = floatOptions(Integrator::Riemann);
    RenderStats first, second;
    const Image a = gpu.render(scene, camera, opt, &first);
    const Image b = gpu.render(scene, camera, opt, &second);
    CHECK_FALSE(first.setupReused);
    CHECK(second.setupReused);
    CHECK(a.pixels == b.pixels);
    CHECK(second.samplesEvaluated == first.samplesEvaluated);
    // A transfer function that is zero on more of the range empties more bricks: the device must get
    // the new grid (a stale one would skip too little and count more samples), the image a fresh
    // renderer's.
    Scene narrower = scene;
    narrower.transferFunction = TransferFunction({{0, 0, 0, 0, 0}, {0.7, 0, 0, 0, 0}, {1, 1, 1, 1, 1.2}},
                                                 EmissionModel::ColourTimesExtinction);
    RenderStats changed, fresh;
    const Image c = gpu.render(narrower, camera, opt, &changed);
    VulkanRenderer other;
    const Image d = other.render(narrower, camera, opt, &fresh);
    CHECK_FALSE(changed.setupReused);
    CHECK(c.pixels == d.pixels);
    CHECK(changed.samplesEvaluated == fresh.samplesEvaluated);
    CHECK(changed.samplesEvaluated < first.samplesEvaluated);
    // Skipping off, then on again: the placeholder replaced the bricks on the device, so they go up again.
    RenderOptions full = opt;
    full.skipEmptySpace = false;
    RenderStats off, again;
    gpu.render(narrower, camera, full, &off);
    const Image e = gpu.render(narrower, camera, opt, &again);
    CHECK(e.pixels == d.pixels);
    CHECK(again.samplesEvaluated == fresh.samplesEvaluated);
}

TEST_CASE("Vulkan keeps the uploaded volume and renders repeatably") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    const Scene scene = blobScene();
    const RenderOptions opt = floatOptions(Integrator::Coupled);
    RenderStats first, second;
    const Image a = gpu.render(scene, obliqueCamera(scene), opt, &first);
    const Image b = gpu.render(scene, obliqueCamera(scene), opt, &second);
    CHECK(a.pixels == b.pixels);
    // Another volume replaces the uploaded one: the same values in float32 give the same image.
    const Scene other = blobScene(VoxelType::Float32);
    CHECK(maxDifference(a, gpu.render(other, obliqueCamera(other), opt)) <= kFixedStep);
}

// A format's own resolution: what the texels can hold between 0 and full scale.
double formatQuantum(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return 1.0 / 255.0;
    case VoxelType::UInt16: return 1.0 / 65535.0;
    case VoxelType::Float32: break;
    }
    return 1e-7;
}

// The device's filter for `type`, or nothing where the device cannot filter that format linearly.
std::optional<SamplerProbe> probeIfFilterable(VulkanRenderer& gpu, VoxelType type) {
    try {
        return gpu.probeSampler(type);
    } catch (const Error& e) {
        // Vulkan requires linear filtering of R8 unorm; R16 unorm and R32 float are optional.
        CHECK(type != VoxelType::UInt8);
        MESSAGE(e.what());
        return std::nullopt;
    }
}

TEST_CASE("Vulkan sampler probe: exact at the texel centres, within the reported sub-texel precision between") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    for (auto type : {VoxelType::UInt8, VoxelType::UInt16, VoxelType::Float32}) {
        CAPTURE(voxelTypeName(type));
        const std::optional<SamplerProbe> found = probeIfFilterable(gpu, type);
        if (!found) continue;
        const SamplerProbe& probe = *found;
        MESSAGE(probe.format, ": max error ", probe.maxError, " (", probe.effectiveBits(), " bits; the device reports ",
                probe.subTexelPrecisionBits, " sub-texel bits)");
        REQUIRE(probe.weight.size() == 4097);
        REQUIRE(probe.read.size() == probe.weight.size());
        CHECK(probe.read.front() == 0.0);
        CHECK(probe.read.back() == 1.0);
        CHECK(probe.subTexelPrecisionBits >= 4);  // the Vulkan minimum
        // Weights on a grid of 2^-bits, then the result rounded to the format's own resolution at worst.
        CHECK(probe.maxError <= std::ldexp(1.0, -probe.subTexelPrecisionBits) + formatQuantum(type));
        // Readings never go back as the weight grows: a filter that does would put ridges into an image.
        CHECK(std::is_sorted(probe.read.begin(), probe.read.end()));
    }
}

// A ramp along x (voxel values 0, 17, ..., 255) with colour s and extinction s / 2 per voxel: smooth,
// so that a bounded error in the interpolated value gives a bounded error in the image.
Scene rampScene(VoxelType type) {
    auto v = std::make_shared<Volume>(glm::ivec3(16, 12, 14), type);
    for (int z = 0; z < v->dims.z; ++z)
        for (int y = 0; y < v->dims.y; ++y)
            for (int x = 0; x < v->dims.x; ++x) setVoxel(*v, v->index(x, y, z), 17 * x);
    v->range = ValueRange{0.0, 255.0};
    return Scene{v, std::nullopt, GridConvention::CellCentred,
                 TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, 0.5}}, EmissionModel::Colour)};
}

// The sampler path against the shader's interpolation on the same device. Where the probe finds the
// filter exact (lavapipe's R16 and R32 float), the images agree as closely as the CPU and shader do.
// Where it does not, each interpolated value moves by at most delta = probe error x the jump between
// neighbouring voxels (1/15 on the ramp). Along a ray of length L, with c tau = s^2 / 2 (slope <= 1,
// at most 1/2) and tau = s / 2 (slope 1/2), the Riemann sum's colour moves by at most
// L delta + (1/2) L (L delta / 2) and its alpha by L delta / 2. The noisy blob, whose transfer function
// jumps, is only reported there: a value moved across a jump changes a sample completely. With either
// interpolation, skipping empty space changes no bit.
TEST_CASE("Vulkan sampler interpolation agrees with the shader's as closely as the probe allows") {
    if (!haveVulkan()) return;
    VulkanRenderer shader;
    VulkanRenderer sampler("", VulkanInterpolation::Sampler);
    for (auto type : {VoxelType::UInt8, VoxelType::UInt16, VoxelType::Float32}) {
        CAPTURE(voxelTypeName(type));
        const std::optional<SamplerProbe> found = probeIfFilterable(sampler, type);
        if (!found) continue;
        const SamplerProbe& probe = *found;
        const bool exact = probe.maxError <= 1e-7;
        for (const Scene& scene : {rampScene(type), blobScene(type)}) {
            const bool ramp = scene.transferFunction.points().size() == 2;
            const Camera camera = obliqueCamera(scene);
            const double length = glm::length(scene.box().size());
            const double delta = probe.maxError / 15.0;
            for (auto integrator : {Integrator::Riemann, Integrator::Coupled}) {
                CAPTURE(integratorName(integrator));
                const RenderOptions opt = floatOptions(integrator);
                RenderStats stats;
                const Image a = shader.render(scene, camera, opt);
                const Image b = sampler.render(scene, camera, opt, &stats);
                const double d = maxDifference(a, b);
                MESSAGE(probe.format, (ramp ? " ramp " : " blob "), integratorName(integrator), ": max difference ", d,
                        " of values up to ", maxValue(a), " (probe error ", probe.maxError, ")");
                CHECK(stats.interpolation == "sampler");
                // Filtered values stay between their neighbours, so skipping empty bricks stays exact.
                RenderOptions full = opt;
                full.skipEmptySpace = false;
                CHECK(sampler.render(scene, camera, full).pixels == b.pixels);
                CHECK(maxValue(a) > 0.1);
                if (exact)
                    CHECK(d <= (integrator == Integrator::Riemann ? kFixedStep : 4 * opt.adaptive.tolerance));
                else if (ramp && integrator == Integrator::Riemann)
                    CHECK(d <= length * delta + 0.25 * length * length * delta + kFixedStep);
            }
        }
    }
    CHECK_THROWS_WITH_AS(parseInterpolation("nearest", "--interpolation"),
                         doctest::Contains("--interpolation: unknown interpolation 'nearest'"), Error);
}

TEST_CASE("Vulkan rejects what it cannot do") {
    if (!haveVulkan()) return;
    VulkanRenderer gpu;
    const Scene scene = linearScene();
    RenderOptions opt;  // double precision
    CHECK_THROWS_WITH_AS(gpu.render(scene, obliqueCamera(scene), opt), doctest::Contains("single precision"), Error);
    opt.precision = Precision::Float;
    opt.samplingRate = 0.0;
    CHECK_THROWS_AS(gpu.render(scene, obliqueCamera(scene), opt), Error);
    CHECK_THROWS_WITH_AS(VulkanRenderer("no such device"), doctest::Contains("no Vulkan device matches"), Error);
    CHECK_THROWS_WITH_AS(VulkanRenderer("99"), doctest::Contains("no Vulkan device matches"), Error);
}
