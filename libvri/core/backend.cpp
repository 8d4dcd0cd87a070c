#include "libvri/core/backend.h"

#include "libvri/util/error.h"

namespace vri {

namespace {

constexpr std::string_view kInterpolationNames[] = {"shader", "sampler"};

}  // namespace

std::string_view interpolationName(VulkanInterpolation i) { return kInterpolationNames[int(i)]; }

Backend parseBackend(std::string_view name, const std::string& what) {
    if (name == "cpu") return Backend::Cpu;
    if (name == "vulkan") return Backend::Vulkan;
    throw Error(what + ": unknown backend '" + std::string(name) + "' (expected cpu or vulkan)");
}

VulkanInterpolation parseInterpolation(std::string_view name, const std::string& what) {
    for (int i = 0; i < 2; ++i)
        if (name == kInterpolationNames[i]) return VulkanInterpolation(i);
    throw Error(what + ": unknown interpolation '" + std::string(name) + "' (expected shader or sampler)");
}

}  // namespace vri
