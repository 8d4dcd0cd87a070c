#include "libvri/vulkan/vulkan_texture.h"

#include <cstring>
#include <string>
#include <utility>

#include "libvri/util/error.h"
#include "libvri/vulkan/vulkan_context.h"

namespace vri {

VolumeTextureFormat volumeTextureFormat(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return {VK_FORMAT_R8_UNORM, "R8 unorm", 255.0f};
    case VoxelType::UInt16: return {VK_FORMAT_R16_UNORM, "R16 unorm", 65535.0f};
    case VoxelType::Float32: break;
    }
    return {VK_FORMAT_R32_SFLOAT, "R32 float", 1.0f};
}

VulkanTexture3D::VulkanTexture3D(const VulkanContext& context, VkExtent3D extent, VkFormat format,
                                 const char* formatName, const void* texels, std::size_t bytes)
    : device_(context.device()) {
    const std::string device = "Vulkan device '" + context.info().name + "'";
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if ((context.imageFeatures(format) & needed) != needed)
        throw Error(device + " cannot filter " + formatName + " images linearly (use the shader's interpolation)");
    const std::uint32_t limit = context.properties().limits.maxImageDimension3D;
    if (extent.width > limit || extent.height > limit || extent.depth > limit)
        throw Error("the volume (" + std::to_string(extent.width) + "x" + std::to_string(extent.height) + "x" +
                    std::to_string(extent.depth) + ") is larger than the " + std::to_string(limit) +
                    " texels per axis of a 3D image on " + device);

    const VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                                 nullptr,
                                 0,
                                 VK_IMAGE_TYPE_3D,
                                 format,
                                 extent,
                                 1,
                                 1,
                                 VK_SAMPLE_COUNT_1_BIT,
                                 VK_IMAGE_TILING_OPTIMAL,
                                 VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                 VK_SHARING_MODE_EXCLUSIVE,
                                 0,
                                 nullptr,
                                 VK_IMAGE_LAYOUT_UNDEFINED};
    vkCheck(vkCreateImage(device_, &info, nullptr, &image_), "vkCreateImage");
    try {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device_, image_, &req);
        int type = context.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        if (type < 0) type = context.memoryType(req.memoryTypeBits, 0);
        if (type < 0) throw Error("Vulkan: no memory type for a 3D image of " + std::to_string(req.size) + " bytes");
        const VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, std::uint32_t(type)};
        vkCheck(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "vkAllocateMemory");
        vkCheck(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory");

        const VulkanBuffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
        std::memcpy(staging.mapped(), texels, bytes);
        staging.flush();
        const VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        context.submitAndWait([&](VkCommandBuffer cmd) {
            VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                                         nullptr,
                                         0,
                                         VK_ACCESS_TRANSFER_WRITE_BIT,
                                         VK_IMAGE_LAYOUT_UNDEFINED,
                                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                         VK_QUEUE_FAMILY_IGNORED,
                                         VK_QUEUE_FAMILY_IGNORED,
                                         image_,
                                         whole};
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr,
                                 0, nullptr, 1, &barrier);
            const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, extent};
            vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
            barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
            barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0,
                                 nullptr, 0, nullptr, 1, &barrier);
        });

        const VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, image_,
                                             VK_IMAGE_VIEW_TYPE_3D, format, {}, whole};
        vkCheck(vkCreateImageView(device_, &viewInfo, nullptr, &view_), "vkCreateImageView");
        // Normalised coordinates: Vulkan allows unnormalised ones for 1D and 2D images only.
        const VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                                              nullptr,
                                              0,
                                              VK_FILTER_LINEAR,
                                              VK_FILTER_LINEAR,
                                              VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                              0.0f,
                                              VK_FALSE,
                                              1.0f,
                                              VK_FALSE,
                                              VK_COMPARE_OP_ALWAYS,
                                              0.0f,
                                              0.0f,
                                              VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK,
                                              VK_FALSE};
        vkCheck(vkCreateSampler(device_, &samplerInfo, nullptr, &sampler_), "vkCreateSampler");
    } catch (...) {
        release();
        throw;
    }
}

VulkanTexture3D::~VulkanTexture3D() { release(); }

VulkanTexture3D::VulkanTexture3D(VulkanTexture3D&& o) noexcept { *this = std::move(o); }

VulkanTexture3D& VulkanTexture3D::operator=(VulkanTexture3D&& o) noexcept {
    if (this != &o) {
        release();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        image_ = std::exchange(o.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(o.view_, VK_NULL_HANDLE);
        sampler_ = std::exchange(o.sampler_, VK_NULL_HANDLE);
    }
    return *this;
}

void VulkanTexture3D::release() {
    if (!device_) return;
    if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
    if (view_) vkDestroyImageView(device_, view_, nullptr);
    if (image_) vkDestroyImage(device_, image_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    sampler_ = VK_NULL_HANDLE;
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

}  // namespace vri
