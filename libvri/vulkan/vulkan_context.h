#pragma once
// The Vulkan instance, one device with a compute queue, and buffers: what the Vulkan backend
// (vulkan_renderer.cpp) builds on. Private to libvri: only vulkan_*.cpp include the Vulkan headers.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "libvri/vulkan/vulkan_renderer.h"

namespace vri {

// Throws vri::Error "Vulkan: <what> failed (<result>)" unless `result` is VK_SUCCESS.
void vkCheck(VkResult result, const char* what);

class VulkanContext;

// A buffer with its own memory, mapped for as long as it lives when the memory is host-visible.
class VulkanBuffer {
public:
    VulkanBuffer() = default;
    // Prefers device-local memory when `deviceLocal`, host-visible memory otherwise (falling back to any
    // host-visible memory); throws vri::Error when no memory type fits.
    VulkanBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage, bool deviceLocal);
    ~VulkanBuffer();
    VulkanBuffer(VulkanBuffer&& other) noexcept;
    VulkanBuffer& operator=(VulkanBuffer&& other) noexcept;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // null for device-only memory
    bool hostCoherent() const { return coherent_; }
    void invalidate() const;  // makes device writes visible to mapped() reads
    void flush() const;       // makes mapped() writes visible to the device

private:
    void release();
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

class VulkanContext {
public:
    // Creates an instance; throws vri::Error when there is no Vulkan loader or driver.
    VulkanContext();
    // An instance with the device that `selector` names opened (see open()).
    explicit VulkanContext(const std::string& selector) : VulkanContext() { open(selector); }
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    std::vector<VulkanDeviceInfo> devices() const;
    // Opens the device that `selector` names (see VulkanRenderer) with one compute queue.
    void open(const std::string& selector);

    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    VkCommandPool commandPool() const { return pool_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    bool hasFloat64() const { return hasFloat64_; }  // shaderFloat64, enabled when the device has it
    const VkPhysicalDeviceMemoryProperties& memory() const { return memory_; }
    const VulkanDeviceInfo& info() const { return info_; }
    // The index of a memory type among `typeBits` with all of `wanted`, or -1.
    int memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags wanted) const;
    // What the device can do with optimally tiled images of `format`.
    VkFormatFeatureFlags imageFeatures(VkFormat format) const;

    // Records commands into a fresh command buffer, submits them and waits for the device.
    template <class Record>
    void submitAndWait(Record&& record) const {
        VkCommandBuffer cmd = begin();
        record(cmd);
        finish(cmd);
    }

private:
    VkCommandBuffer begin() const;
    void finish(VkCommandBuffer cmd) const;

    VkInstance instance_ = VK_NULL_HANDLE;
    std::vector<VkPhysicalDevice> physical_;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;  // the opened one
    VkPhysicalDeviceProperties properties_{};
    bool hasFloat64_ = false;
    VkPhysicalDeviceMemoryProperties memory_{};
    VulkanDeviceInfo info_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

}  // namespace vri
