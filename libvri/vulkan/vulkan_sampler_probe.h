#pragma once
// VulkanRenderer::probeSampler's measurement, on an open context. Private to libvri.
#include "libvri/vulkan/vulkan_renderer.h"

namespace vri {

class VulkanContext;

SamplerProbe probeSampler(const VulkanContext& context, VoxelType type);

}  // namespace vri
