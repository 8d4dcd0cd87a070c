#pragma once
// The backends behind --backend: the CPU raycaster, and the Vulkan renderer when the build has it
// (-DVRI_VULKAN=ON, VRI_HAVE_VULKAN). The one place vri chooses between them, for the tools and Python.
#include <memory>
#include <string>
#include <vector>

#include "libvri/core/render_option_table.h"

namespace vri {

class RenderBackend {
public:
    // Checks the request against the backend it names (Vulkan: float only, no logged ray) before any
    // device is opened, so the message does not depend on having one; then opens the Vulkan device.
    explicit RenderBackend(const RenderRequest& request);
    ~RenderBackend();
    RenderBackend(const RenderBackend&) = delete;
    RenderBackend& operator=(const RenderBackend&) = delete;

    Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats);
    // The exact method, on the CPU whatever the backend, with the empty space of the first frame; the
    // result stays valid until the next call, which reuses its memory.
    const ExactReference& renderExact(const Scene& scene, const Camera& camera, const ExactReferenceOptions& options);

private:
    struct Vulkan;
    std::unique_ptr<Vulkan> vulkan_;  // the device, opened once; the volume is uploaded by the first render
    std::unique_ptr<OccupancyCache> occupancy_;  // the CPU's empty space, built by the first render
    ExactReference exact_;                       // the exact method's last frame
};

// A Vulkan device as --list-devices shows it.
struct BackendDevice {
    int index = 0;
    std::string name, type, apiVersion;
};
// The Vulkan devices this machine offers; throws vri::Error when the build has no Vulkan backend.
std::vector<BackendDevice> vulkanDevices();

}  // namespace vri
