#pragma once
// A 3D image with a trilinear sampler, the hardware-filtered alternative to reading the volume from a
// storage buffer (vulkan_renderer.cpp, VulkanInterpolation::Sampler). Private to libvri.
#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "libvri/core/voxel_type.h"

namespace vri {

// The 3D image format that holds a volume's voxels for the sampler, and the voxel value of a texel
// that the sampler reads as 1 (unorm formats read v / (2^bits - 1)).
struct VolumeTextureFormat {
    VkFormat format;
    const char* name;
    float unit;
};
VolumeTextureFormat volumeTextureFormat(VoxelType type);

class VulkanContext;

class VulkanTexture3D {
public:
    VulkanTexture3D() = default;
    // An image of `extent` texels of `format`, filled from `texels` (x fastest, tightly packed) and left
    // ready for sampling, with a sampler that filters linearly and clamps to the edge. Throws vri::Error
    // when the device cannot filter `format` linearly (`formatName` says which) or the extent is too large.
    VulkanTexture3D(const VulkanContext& context, VkExtent3D extent, VkFormat format, const char* formatName,
                    const void* texels, std::size_t bytes);
    ~VulkanTexture3D();
    VulkanTexture3D(VulkanTexture3D&& other) noexcept;
    VulkanTexture3D& operator=(VulkanTexture3D&& other) noexcept;

    VkImageView view() const { return view_; }
    VkSampler sampler() const { return sampler_; }

private:
    void release();
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace vri
