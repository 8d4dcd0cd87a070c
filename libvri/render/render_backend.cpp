#include "libvri/render/render_backend.h"

#include "libvri/util/error.h"
#include "libvri/core/cpu_renderer.h"
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

std::vector<BackendDevice> vulkanDevices() {
    std::vector<BackendDevice> devices;
    for (const VulkanDeviceInfo& d : VulkanRenderer::listDevices())
        devices.push_back({d.index, d.name, d.type, d.apiVersion});
    return devices;
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

std::vector<BackendDevice> vulkanDevices() {
    throw Error("--list-devices: this build has no Vulkan backend (configured with -DVRI_VULKAN=OFF)");
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
