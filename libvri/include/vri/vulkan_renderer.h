#pragma once
// The Vulkan compute backend: the CPU raycaster's methods (render.h) in single precision on a Vulkan
// device (a GPU, or Mesa's lavapipe on the CPU). The Vulkan headers stay in libvri/src/vulkan_*.cpp.
//
// What differs from vri::render() with Precision::Float: float arithmetic whose rounding the device
// chooses (exp, division), no per-ray log. Empty space is skipped as on the CPU (the same bricks),
// which never changes an image, only the samples evaluated. The rays themselves
// (entry and exit points, world length per unit of ray) are clipped on the CPU in double precision
// exactly as render() does, so both backends integrate along the same segments.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vri/image.h"
#include "vri/render.h"

namespace vri {

struct VulkanDeviceInfo {
    int index = 0;
    std::string name;
    std::string type;        // "discrete-gpu", "integrated-gpu", "virtual-gpu", "cpu", "other"
    std::string apiVersion;  // "1.3.239"
};

class VulkanRenderer {
public:
    // Every physical device of the Vulkan loader; empty when there is no loader, driver or device.
    static std::vector<VulkanDeviceInfo> listDevices();

    // `device`: an index into listDevices(), a case-insensitive substring of a device's name, or empty
    // for the first device. Throws vri::Error when Vulkan is unavailable or nothing matches.
    explicit VulkanRenderer(const std::string& device = "");
    ~VulkanRenderer();
    VulkanRenderer(const VulkanRenderer&) = delete;
    VulkanRenderer& operator=(const VulkanRenderer&) = delete;

    const VulkanDeviceInfo& device() const;

    // As vri::render() in float. The scene's volume is uploaded on first use and kept for as long as
    // the same Volume object is rendered; upload and pipeline creation are not in stats->seconds.
    // Throws vri::Error on what render() rejects, on Precision::Double, a log pixel, or a volume
    // larger than the device's largest storage buffer.
    Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats = nullptr);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vri
