#include "libvri/vulkan/vulkan_renderer.h"

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "libvri/core/frame_average.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/vulkan/vulkan_context.h"
#include "libvri/vulkan/vulkan_pipelines.h"
#include "libvri/vulkan/vulkan_sampler_probe.h"
#include "libvri/vulkan/vulkan_texture.h"

// SPIR-V of shaders/*.comp, compiled at build time (libvri/CMakeLists.txt).
#include "march_spv.h"
#include "simpson_spv.h"

namespace vri {

namespace {

// The shaders' uniform block Params (shaders/common.glsl), std140.
struct Params {
    float scale[4], offset[4], maxCoord[4];
    std::int32_t maxBase[4], stride[4];
    float dims[4], eyeU[4];
    float lo, invRange, samplingRate, earlyTermination;
    float h0, hMin, hMax, epsPerVoxel;
    std::int32_t width, height, tfCount, accepted;
    std::int32_t bricks[4];  // w: 1 when skipping empty space
    float maxIndex[4];
    float texel[4];  // the sampler: 1 / dims, and in w the voxel value of a texel that reads 1
    std::int32_t region[4];  // x, y, width, height: the pixels rendered
    // The camera and the box, in double for the shader's rays (common.glsl's makeRay).
    double eye[4], forward[4], right[4], up[4], boxLo[4], boxHi[4];
};
static_assert(sizeof(Params) == 416 && offsetof(Params, eye) == 224);

enum Binding { kParams, kVolume, kTransferFunction, kTotals, kOutput, kOccupancy, kVolumeTexture, kPreintegration, kBindings };

// The frame's counters that the shaders sum (common.glsl's Totals): each a 64-bit count in two 32-bit
// words. Simpson's eight are AdaptiveCounts in the order of simpson.comp; marching uses the first two.
constexpr int kTotalCount = 9;
constexpr int kTotalRaysHit = 8;

std::vector<VkDescriptorType> bindingTypes() {
    std::vector<VkDescriptorType> types(kBindings, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    types[kParams] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    types[kVolumeTexture] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    return types;
}


int voxelTypeConstant(const Scene& scene) {
    if (!scene.volume) return 3;
    switch (scene.volume->type) {
    case VoxelType::UInt8: return 0;
    case VoxelType::UInt16: return 1;
    case VoxelType::Float32: break;
    }
    return 2;
}

// Per transfer function point: s, r, g, b, tau and the differences to the next point, rounded to float
// from double as TransferFunction::operator()<float> rounds them.
std::vector<float> transferFunctionTable(const TransferFunction& tf) {
    const auto& p = tf.points();
    std::vector<float> out;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const TransferFunctionPoint& a = p[i];
        const TransferFunctionPoint& b = i + 1 < p.size() ? p[i + 1] : a;
        for (double v : {a.s, a.r, a.g, a.b, a.tau, b.s - a.s, b.r - a.r, b.g - a.g, b.b - a.b, b.tau - a.tau})
            out.push_back(static_cast<float>(v));
    }
    return out;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct VulkanRenderer::Impl {
    VulkanContext context;
    const VulkanInterpolation interpolation;
    VulkanPipelines kernels;
    VkShaderModule march, simpson;

    std::shared_ptr<const Volume> volume;  // the uploaded one, kept alive so that its address stays unique
    // Whichever of the two the interpolation does not read holds a one-voxel placeholder, since every
    // binding needs a valid descriptor.
    VulkanBuffer volumeBuffer;
    VulkanTexture3D volumeTexture;
    VulkanBuffer params, transferFunction, totals, output, occupancy;
    VulkanBuffer preintegration;  // the pre-integration table in float (march.comp), a placeholder otherwise
    // The empty-space bricks, built as the CPU builds them and kept while volume, convention and transfer
    // function stay (occupancy_cache.h); `occupancy` holds the uploaded copy of `uploadedGrid`.
    OccupancyCache grids;
    const OccupancyGrid* uploadedGrid = nullptr;

    Impl(const std::string& selector, VulkanInterpolation interpolation)
        : context(selector), interpolation(interpolation), kernels(context, bindingTypes()),
          march(kernels.module(march_spv, sizeof(march_spv))),
          simpson(kernels.module(simpson_spv, sizeof(simpson_spv))),
          params(context, sizeof(Params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, false) {
        // The shaders make their rays in double (common.glsl's makeRay), so that they are the CPU's.
        if (!context.hasFloat64())
            throw Error("Vulkan device '" + context.info().name +
                        "' has no 64-bit floats (shaderFloat64), which the renderer's ray setup needs");
    }

    ~Impl() { vkDeviceWaitIdle(context.device()); }  // before the buffers go

    void checkRange(VkDeviceSize bytes, const std::string& what, const std::string& hint = "") const {
        const VkDeviceSize limit = context.properties().limits.maxStorageBufferRange;
        if (bytes > limit)
            throw Error(what + " needs " + std::to_string(bytes) + " bytes in one storage buffer, more than the " +
                        std::to_string(limit) + " that Vulkan device '" + context.info().name + "' allows" + hint);
    }

    // Uploads the volume in its native type: into a storage buffer padded to whole 32-bit words (the
    // shader reads uint[]), or into a 3D image for the sampler. The other binding gets a placeholder.
    void upload(const std::shared_ptr<const Volume>& v) {
        if (volume == v && volumeBuffer.handle()) return;
        volume.reset();
        volumeBuffer = VulkanBuffer();
        volumeTexture = VulkanTexture3D();
        const bool sampled = v && interpolation == VulkanInterpolation::Sampler;
        const std::size_t bytes = v && !sampled ? v->byteCount() : 0;
        const VkDeviceSize padded = std::max<VkDeviceSize>(4, (bytes + 3) / 4 * 4);
        if (bytes)
            checkRange(padded, "the " + std::string(voxelTypeName(v->type)) + " volume",
                       " (--interpolation sampler reads it from a 3D image instead)");
        VulkanBuffer target(context, padded, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        const auto fill = [&](void* to) {
            std::memset(to, 0, padded);
            if (bytes) std::memcpy(to, v->bytes.data(), bytes);
        };
        if (target.mapped()) {
            fill(target.mapped());
            target.flush();
        } else {
            const VulkanBuffer staging(context, padded, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
            fill(staging.mapped());
            staging.flush();
            context.submitAndWait([&](VkCommandBuffer cmd) {
                const VkBufferCopy region{0, 0, padded};
                vkCmdCopyBuffer(cmd, staging.handle(), target.handle(), 1, &region);
            });
        }
        if (sampled) {
            const VolumeTextureFormat f = volumeTextureFormat(v->type);
            const VkExtent3D extent{std::uint32_t(v->dims.x), std::uint32_t(v->dims.y), std::uint32_t(v->dims.z)};
            volumeTexture = VulkanTexture3D(context, extent, f.format, f.name, v->bytes.data(), v->byteCount());
        } else {
            const std::uint8_t zero = 0;
            volumeTexture = VulkanTexture3D(context, {1, 1, 1}, VK_FORMAT_R8_UNORM, "R8 unorm", &zero, 1);
        }
        volumeBuffer = std::move(target);
        volume = v;
    }

    // A host-visible buffer of at least `bytes`, reused across renders.
    void ensure(VulkanBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage, const std::string& what) {
        checkRange(bytes, what);
        if (buffer.handle() && buffer.size() >= bytes) return;
        buffer = VulkanBuffer();
        buffer = VulkanBuffer(context, bytes, usage, false);
    }

    void bind() const {
        const VulkanBuffer* buffers[] = {&params, &volumeBuffer, &transferFunction, &totals, &output, &occupancy};
        for (std::uint32_t b = 0; b < kVolumeTexture; ++b) kernels.bind(b, *buffers[b]);
        kernels.bind(kVolumeTexture, volumeTexture);
        kernels.bind(kPreintegration, preintegration);
    }
};

std::vector<VulkanDeviceInfo> VulkanRenderer::listDevices() {
    try {
        return VulkanContext().devices();
    } catch (const Error&) {
        return {};
    }
}

VulkanRenderer::VulkanRenderer(const std::string& device, VulkanInterpolation interpolation)
    : impl_(std::make_unique<Impl>(device, interpolation)) {}

VulkanRenderer::~VulkanRenderer() = default;

const VulkanDeviceInfo& VulkanRenderer::device() const { return impl_->context.info(); }

SamplerProbe VulkanRenderer::probeSampler(VoxelType type) { return vri::probeSampler(impl_->context, type); }

void VulkanRenderer::validateOptions(const RenderOptions& options) {
    if (options.precision != Precision::Float)
        throw Error("the Vulkan backend renders in single precision only (precision float)");
    if (options.logPixel) throw Error("the Vulkan backend does not log a ray (the per-ray log is CPU only)");
    if (options.terminationBound > 0.0)
        throw Error("early termination 'auto': the Vulkan backend takes a transparency threshold only");
}

Image VulkanRenderer::render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats) {
    if (scene.sparse) throw Error("the Vulkan backend renders dense volumes only, not a sparse one");
    validateRender(scene, camera, options);
    validateOptions(options);
    if (options.frames > 1)
        return averageFrames(options, stats, [&](const RenderOptions& frame, RenderStats* frameStats) {
            return render(scene, camera, frame, frameStats);
        });
    Impl& m = *impl_;
    const bool simpson = isSimpson(options.integrator);
    const bool preintegrated = options.integrator == Integrator::Preintegrated;
    const PixelRegion area = renderedRegion(options.region, camera);  // the image holds these pixels
    const int width = area.width, height = area.height;
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    const std::uint32_t groupsX = (width + 7) / 8, groupsY = (height + 7) / 8;
    const auto& limits = m.context.properties().limits;
    if (groupsX > limits.maxComputeWorkGroupCount[0] || groupsY > limits.maxComputeWorkGroupCount[1])
        throw Error("the image is too large for one dispatch on Vulkan device '" + m.context.info().name + "'");

    // Setup, not timed: the volume (once per volume), the pipeline (once per combination) and the
    // empty-space bricks (once per volume, convention and transfer function).
    RenderStats local;
    const auto setupStart = std::chrono::steady_clock::now();
    m.upload(scene.volume);
    const int emission = scene.transferFunction.emission() == EmissionModel::ColourTimesExtinction ? 0 : 1;
    const AdaptiveParameters adaptive = simpsonParameters(options);
    const int sampler = m.interpolation == VulkanInterpolation::Sampler ? 1 : 0;
    // Specialisation constants (common.glsl, march.comp, simpson.comp).
    const VkPipeline pipeline =
        simpson ? m.kernels.pipeline(m.simpson, {voxelTypeConstant(scene), emission,
                                                 adaptive.coupling == Coupling::Coupled ? 1 : 0, 0, sampler})
                : m.kernels.pipeline(m.march, {voxelTypeConstant(scene), emission, int(options.placement),
                                               options.integrator == Integrator::Composite ? 1 : 0, sampler,
                                               preintegrated ? options.preintegrationOrder : 0});
    // Pre-integration: the CPU's table, built for this render (as the CPU renderer builds it, in the
    // setup), its float entries uploaded; its measured error goes to the stats as the CPU's does.
    std::optional<PreintegrationTable> table;
    if (preintegrated) {
        table.emplace(scene.transferFunction, preintegrationSegmentLength(scene, options), options.preintegrationSize,
                      options.preintegrationOrder);
        local.preintegration = RenderStats::Preintegration{.size = table->size(),
                                                           .order = table->order(),
                                                           .segmentLength = table->segmentLength(),
                                                           .error = table->check(scene.transferFunction)};
    }
    {
        const std::size_t entries = table ? std::size_t(table->size()) * table->size() * 4 : 1;
        const std::size_t floats = table && table->order() == 2 ? 2 * entries + 4 : entries;
        m.ensure(m.preintegration, floats * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "the pre-integration table");
        auto* to = static_cast<float*>(m.preintegration.mapped());
        if (table) {
            std::memcpy(to, table->values<float>(), entries * sizeof(float));
            if (table->order() == 2) {
                std::memcpy(to + entries, table->slopes<float>(), entries * sizeof(float));
                std::memcpy(to + 2 * entries, table->upperBound<float>(), 4 * sizeof(float));
            }
        } else {
            to[0] = 0.0f;
        }
        m.preintegration.flush();
    }
    const std::vector<float> tf = transferFunctionTable(scene.transferFunction);
    m.ensure(m.transferFunction, tf.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "the transfer function");
    // Host-visible buffers: one vec4 of colour per pixel, and the frame's counters.
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    m.ensure(m.output, checkedBytes("Vulkan: a " + size + " image", {pixels, 16}), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             "the image");
    m.ensure(m.totals, 2 * kTotalCount * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "the counters");
    // Empty-space skipping: the CPU's bricks, from the cache, uploaded when they are not the ones the
    // device already holds. Without skipping the binding still needs a buffer: a zero placeholder.
    const OccupancyGrid* grid = nullptr;
    bool gridReused = false;
    if (scene.volume && options.skipEmptySpace) {
        const auto entry = m.grids.grid(scene.volume, scene.convention, scene.transferFunction);
        grid = &entry.structure;
        gridReused = entry.reused;
        local.emptyBrickFraction = grid->emptyFraction();
    }
    if (!m.occupancy.handle() || grid != m.uploadedGrid || !gridReused) {
        std::vector<std::uint8_t> empty = grid ? grid->emptyFlags() : std::vector<std::uint8_t>(4, 0);
        empty.resize((empty.size() + 3) / 4 * 4, 0);
        m.ensure(m.occupancy, empty.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "the empty-space bricks");
        std::memcpy(m.occupancy.mapped(), empty.data(), empty.size());
        m.occupancy.flush();
        m.uploadedGrid = grid;
    }
    local.setupSeconds = secondsSince(setupStart);
    local.setupReused = gridReused;

    const auto start = std::chrono::steady_clock::now();
    // The uniforms, with the values GridSampler<T, float>, placeSamples<float> and AdaptiveSimpsonRay<float> use.
    using Vec = glm::vec3;
    const Box box = scene.box();
    const Vec dims(scene.dims());
    const Vec eyeU(box.toTexture(camera.eye()));
    Params p{};
    if (scene.volume) {
        const Volume& v = *scene.volume;
        const GridIndexing g(v.dims, scene.convention);
        for (int a = 0; a < 3; ++a) {
            p.scale[a] = static_cast<float>(g.scale[a]);
            p.offset[a] = static_cast<float>(g.offset[a]);
            p.maxCoord[a] = static_cast<float>(g.maxCoord[a]);
            p.maxBase[a] = g.maxBase[a];
            p.stride[a] = static_cast<std::int32_t>(g.stride[a]);
            p.texel[a] = 1.0f / static_cast<float>(v.dims[a]);
        }
        p.texel[3] = volumeTextureFormat(v.type).unit;
        const ValueRange r = v.normalisationRange();
        p.lo = static_cast<float>(r.lo);
        p.invRange = r.hi > r.lo ? static_cast<float>(1.0 / (r.hi - r.lo)) : 0.0f;
    }
    for (int a = 0; a < 3; ++a) {
        p.dims[a] = dims[a];
        p.eyeU[a] = eyeU[a];
    }
    p.samplingRate = static_cast<float>(options.samplingRate);
    p.earlyTermination = static_cast<float>(options.earlyTermination);
    p.h0 = static_cast<float>(adaptive.h0);
    p.hMin = static_cast<float>(adaptive.hMin);
    p.hMax = static_cast<float>(adaptive.hMax);
    p.epsPerVoxel = static_cast<float>(adaptive.tolerance / adaptive.h0);
    p.width = camera.width();  // the rays are the whole image's
    p.height = camera.height();
    p.region[0] = area.x;
    p.region[1] = area.y;
    p.region[2] = area.width;
    p.region[3] = area.height;
    p.tfCount = static_cast<std::int32_t>(scene.transferFunction.points().size());
    p.accepted = adaptive.accepted == AcceptedValue::Richardson ? 0 : 1;
    const CameraBasis basis = camera.basis();
    for (int a = 0; a < 3; ++a) {
        p.eye[a] = camera.eye()[a];
        p.forward[a] = basis.forward[a];
        p.right[a] = basis.right[a];
        p.up[a] = basis.up[a];
        p.boxLo[a] = box.lo[a];
        p.boxHi[a] = box.hi[a];
    }
    p.eye[3] = camera.spec().zoom;
    p.forward[3] = basis.tanHalfX;
    p.right[3] = basis.tanHalfY;
    p.up[3] = basis.centre.x;
    p.boxLo[3] = basis.centre.y;
    p.boxHi[3] = options.jitter ? double(options.seed) : -1.0;  // march.comp: no jitter below 0
    if (table) {
        p.stride[3] = table->size();
        p.dims[3] = static_cast<float>(table->segmentLength());  // as the CPU's float path rounds it
    }
    if (grid) {
        for (int a = 0; a < 3; ++a) {
            p.bricks[a] = grid->bricks()[a];
            p.maxIndex[a] = static_cast<float>(grid->maxIndex()[a]);
        }
        p.bricks[3] = 1;
    }
    std::memcpy(m.params.mapped(), &p, sizeof p);
    std::memcpy(m.transferFunction.mapped(), tf.data(), tf.size() * sizeof(float));
    std::memset(m.totals.mapped(), 0, m.totals.size());
    for (const VulkanBuffer* b : {&m.params, &m.transferFunction, &m.totals}) b->flush();

    // The shaders make and clip each pixel's ray (in double, as render() does) and sum the counters.
    m.bind();
    m.kernels.dispatch(pipeline, groupsX, groupsY);
    m.output.invalidate();
    m.totals.invalidate();

    Image image(width, height);
    std::memcpy(image.pixels.data(), m.output.mapped(), pixels * 16);
    const auto* words = static_cast<const std::uint32_t*>(m.totals.mapped());
    const auto total = [&](int i) { return std::uint64_t(words[2 * i]) | std::uint64_t(words[2 * i + 1]) << 32; };
    local.seconds = secondsSince(start);
    local.raysHit = total(kTotalRaysHit);
    AdaptiveCounts counts;
    if (simpson) {
        counts.pointsUsed = total(0);
        counts.pointsEvaluated = total(1);
        counts.innerTries = total(2);
        counts.innerFailures = total(3);
        counts.outerTries = total(4);
        counts.outerFailures = total(5);
        counts.outerSteps = total(6);
        counts.acceptedAtMinimum = total(7);
    }
    local.rays = pixels;
    local.samplesPlaced = simpson ? counts.pointsUsed : total(0);
    local.samplesEvaluated = simpson ? counts.pointsEvaluated : total(1);
    if (simpson) local.adaptive = counts;
    local.backend = "vulkan";
    local.device = m.context.info().name;
    local.interpolation = interpolationName(m.interpolation);
    local.nonfinite = findNonFinitePixels(image);
    if (stats) *stats = local;
    return image;
}

}  // namespace vri
