#pragma once
// The Vulkan compute backend: the CPU raycaster's methods (cpu_renderer.h; both render against
// render_contract.h) in single precision on a Vulkan device (a GPU, or Mesa's lavapipe on the CPU). The
// Vulkan headers stay in libvri/vulkan/*.cpp.
//
// What differs from vri::render() with Precision::Float: float arithmetic whose rounding the device
// chooses (exp, division), no per-ray log, and, with VulkanInterpolation::Sampler, the device's own
// trilinear filtering. Empty space is skipped as on the CPU (the same bricks),
// which never changes an image, only the samples evaluated. The shaders make and clip each pixel's
// ray themselves in double precision with render()'s operations in its order (entry and exit points,
// world length per unit of ray), so both backends integrate along the same segments; this needs a
// device with 64-bit floats (shaderFloat64). The frame's counters are summed on the device too, so
// stats->seconds is the device's work and the image's copy back; the empty-space bricks are setup,
// built and uploaded once while the volume, convention and transfer function stay (as on the CPU).
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/core/backend.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/image.h"
#include "libvri/core/voxel_type.h"

namespace vri {

struct VulkanDeviceInfo {
    int index = 0;
    std::string name;
    std::string type;        // "discrete-gpu", "integrated-gpu", "virtual-gpu", "cpu", "other"
    std::string apiVersion;  // "1.3.239"
};

// What a device's trilinear filter makes of one axis of a 3D image of a voxel type: a 2x1x1 image
// holding 0 and full scale (255, 65535, 1.0), read at evenly spaced points from the centre of the first
// texel to the second's. The exact reading is the second texel's weight; the error is what the
// sampler's weights and its arithmetic add to every interpolated voxel value, as a fraction of the
// difference between neighbouring voxels.
struct SamplerProbe {
    std::string format;           // "R8 unorm", "R16 unorm", "R32 float"
    int subTexelPrecisionBits = 0;  // what the device reports (VkPhysicalDeviceLimits)
    std::vector<double> weight;   // the exact weight at each point
    std::vector<double> read;     // what the sampler returned, in units of full scale
    double maxError = 0.0;        // max |read - weight|
    double effectiveBits() const;  // -log2(maxError): the precision the filter delivers; inf when exact
};

class VulkanRenderer {
public:
    // Every physical device of the Vulkan loader; empty when there is no loader, driver or device.
    static std::vector<VulkanDeviceInfo> listDevices();

    // `device`: an index into listDevices(), a case-insensitive substring of a device's name, or empty
    // for the first device. Throws vri::Error when Vulkan is unavailable or nothing matches.
    explicit VulkanRenderer(const std::string& device = "",
                            VulkanInterpolation interpolation = VulkanInterpolation::Shader);
    ~VulkanRenderer();
    VulkanRenderer(const VulkanRenderer&) = delete;
    VulkanRenderer& operator=(const VulkanRenderer&) = delete;

    const VulkanDeviceInfo& device() const;

    // Measures the device's trilinear filtering for volumes of `type` (see SamplerProbe). Throws
    // vri::Error when the device cannot filter that type's format linearly.
    SamplerProbe probeSampler(VoxelType type);

    // As vri::render() in float. The scene's volume is uploaded on first use and kept for as long as
    // the same Volume object is rendered; upload and pipeline creation are not in stats->seconds.
    // Throws vri::Error on what render() rejects, on Precision::Double, a log pixel, or a volume
    // larger than the device's largest storage buffer (or 3D image, or a format the device cannot filter).
    // The constructor throws vri::Error on a device without 64-bit floats.
    Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats = nullptr);
    // Throws vri::Error on the options no Vulkan device can honour (double precision, a logged ray):
    // tools check them before opening a device, so the message does not depend on having one.
    static void validateOptions(const RenderOptions& options);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vri
