#include "common/render_backend.h"

#include <iostream>
#include <vector>

#include "common/cli.h"
#include "libvri/core/occupancy_cache.h"

#if VRI_HAVE_VULKAN
#include "libvri/vulkan/vulkan_renderer.h"

namespace vri {

struct RenderBackend::Vulkan {
    Vulkan(const std::string& device, VulkanInterpolation interpolation) : renderer(device, interpolation) {}
    VulkanRenderer renderer;
};

RenderBackend::RenderBackend(const RenderRequest& request) : occupancy_(std::make_unique<OccupancyCache>()) {
    if (request.backend != Backend::Vulkan) return;
    VulkanRenderer::validateOptions(request.options);
    vulkan_ = std::make_unique<Vulkan>(request.device, request.interpolation);
}

Image RenderBackend::render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats) {
    return vulkan_ ? vulkan_->renderer.render(scene, camera, options, stats)
                   : vri::render(scene, camera, options, stats, occupancy_.get());
}

int listVulkanDevices(std::string_view tool) {
    const std::vector<VulkanDeviceInfo> devices = VulkanRenderer::listDevices();
    if (devices.empty()) {
        std::cerr << tool << ": error: no Vulkan device found\n";
        return kExitError;
    }
    for (const VulkanDeviceInfo& d : devices)
        std::cout << d.index << '\t' << d.name << '\t' << d.type << '\t' << d.apiVersion << '\n';
    return kExitOk;
}

}  // namespace vri

#else  // built with -DVRI_VULKAN=OFF: the CPU only

namespace vri {

struct RenderBackend::Vulkan {};

RenderBackend::RenderBackend(const RenderRequest& request) : occupancy_(std::make_unique<OccupancyCache>()) {
    if (request.backend == Backend::Vulkan)
        throw Error("--backend vulkan: this build has no Vulkan backend (configured with -DVRI_VULKAN=OFF)");
}

Image RenderBackend::render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats) {
    return vri::render(scene, camera, options, stats, occupancy_.get());
}

int listVulkanDevices(std::string_view tool) {
    std::cerr << tool << ": error: --list-devices: this build has no Vulkan backend (configured with -DVRI_VULKAN=OFF)\n";
    return kExitError;
}

}  // namespace vri

#endif

namespace vri {

RenderBackend::~RenderBackend() = default;

const ExactReference& RenderBackend::renderExact(const Scene& scene, const Camera& camera,
                                                 const ExactReferenceOptions& options) {
    renderExactReference(scene, camera, options, occupancy_.get(), exact_);
    return exact_;
}

}  // namespace vri
