#include "libvri/vulkan/vulkan_context.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <utility>

#include "libvri/util/error.h"

namespace vri {

namespace {

std::string resultName(VkResult r) {
    switch (r) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    default: return "VkResult " + std::to_string(static_cast<int>(r));
    }
}

std::string typeName(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

VulkanDeviceInfo describe(VkPhysicalDevice device, int index) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(device, &p);
    return {index, p.deviceName, typeName(p.deviceType),
            std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." + std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) +
                "." + std::to_string(VK_API_VERSION_PATCH(p.apiVersion))};
}

}  // namespace

void vkCheck(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw Error(std::string("Vulkan: ") + what + " failed (" + resultName(result) + ")");
}

VulkanBuffer::VulkanBuffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage, bool deviceLocal)
    : device_(context.device()), size_(size) {
    const VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage,
                                  VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
    vkCheck(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    const auto find = [&](VkMemoryPropertyFlags wanted) { return context.memoryType(req.memoryTypeBits, wanted); };
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
    int type = -1;
    if (deviceLocal) type = find(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = find(host | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (type < 0) type = find(host | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (type < 0) type = find(host);
    if (type < 0) {
        release();
        throw Error("Vulkan: no memory type for a buffer of " + std::to_string(size) + " bytes");
    }
    const VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, std::uint32_t(type)};
    const VkResult allocated = vkAllocateMemory(device_, &alloc, nullptr, &memory_);
    if (allocated != VK_SUCCESS) release();
    vkCheck(allocated, "vkAllocateMemory");
    vkCheck(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
    const VkMemoryPropertyFlags flags = context.memory().memoryTypes[type].propertyFlags;
    coherent_ = flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (flags & host) vkCheck(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
}

VulkanBuffer::~VulkanBuffer() { release(); }

VulkanBuffer::VulkanBuffer(VulkanBuffer&& o) noexcept { *this = std::move(o); }

VulkanBuffer& VulkanBuffer::operator=(VulkanBuffer&& o) noexcept {
    if (this != &o) {
        release();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(o.size_, 0);
        mapped_ = std::exchange(o.mapped_, nullptr);
        coherent_ = o.coherent_;
    }
    return *this;
}

void VulkanBuffer::invalidate() const {
    if (coherent_ || !mapped_) return;
    const VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
    vkCheck(vkInvalidateMappedMemoryRanges(device_, 1, &range), "vkInvalidateMappedMemoryRanges");
}

void VulkanBuffer::flush() const {
    if (coherent_ || !mapped_) return;
    const VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, memory_, 0, VK_WHOLE_SIZE};
    vkCheck(vkFlushMappedMemoryRanges(device_, 1, &range), "vkFlushMappedMemoryRanges");
}

void VulkanBuffer::release() {
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);  // unmaps too
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
}

VulkanContext::VulkanContext() {
    const VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "vri", 1, "vri", 1, VK_API_VERSION_1_2};
    const VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, nullptr, 0, &app, 0, nullptr, 0, nullptr};
    const VkResult r = vkCreateInstance(&info, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        throw Error("no Vulkan device found (no Vulkan driver is installed; Mesa's lavapipe is one that runs on the CPU)");
    vkCheck(r, "vkCreateInstance");
    std::uint32_t count = 0;
    vkCheck(vkEnumeratePhysicalDevices(instance_, &count, nullptr), "vkEnumeratePhysicalDevices");
    physical_.resize(count);
    vkCheck(vkEnumeratePhysicalDevices(instance_, &count, physical_.data()), "vkEnumeratePhysicalDevices");
    physical_.resize(count);
}

VulkanContext::~VulkanContext() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    vkDestroyInstance(instance_, nullptr);
}

std::vector<VulkanDeviceInfo> VulkanContext::devices() const {
    std::vector<VulkanDeviceInfo> out;
    for (std::size_t i = 0; i < physical_.size(); ++i) out.push_back(describe(physical_[i], int(i)));
    return out;
}

void VulkanContext::open(const std::string& selector) {
    const std::vector<VulkanDeviceInfo> all = devices();
    if (all.empty()) throw Error("no Vulkan device found");
    int chosen = -1;
    int index = -1;
    const auto [end, ec] = std::from_chars(selector.data(), selector.data() + selector.size(), index);
    if (selector.empty()) {
        chosen = 0;
    } else if (ec == std::errc() && end == selector.data() + selector.size()) {
        if (index >= 0 && index < int(all.size())) chosen = index;
    } else {
        for (const VulkanDeviceInfo& d : all)
            if (lower(d.name).find(lower(selector)) != std::string::npos) {
                chosen = d.index;
                break;
            }
    }
    if (chosen < 0) {
        std::string names;
        for (const VulkanDeviceInfo& d : all) names += (names.empty() ? "" : ", ") + std::to_string(d.index) + " " + d.name;
        throw Error("--device: no Vulkan device matches '" + selector + "' (devices: " + names + ")");
    }
    const VkPhysicalDevice physical = physicalDevice_ = physical_[chosen];
    info_ = all[chosen];
    vkGetPhysicalDeviceProperties(physical, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical, &memory_);
    if (properties_.apiVersion < VK_API_VERSION_1_2)
        throw Error("Vulkan device '" + info_.name + "' supports API " + info_.apiVersion + ", the shaders need 1.2");

    std::uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, families.data());
    std::uint32_t family = familyCount;
    for (std::uint32_t i = 0; i < familyCount && family == familyCount; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) family = i;
    if (family == familyCount) throw Error("Vulkan device '" + info_.name + "' has no compute queue");

    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
    // 64-bit floats where the device has them: the renderer's shaders make their rays in double.
    VkPhysicalDeviceFeatures supported{}, enabled{};
    vkGetPhysicalDeviceFeatures(physical, &supported);
    enabled.shaderFloat64 = supported.shaderFloat64;
    hasFloat64_ = supported.shaderFloat64 == VK_TRUE;
    const VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, nullptr, 0, 1, &queueInfo, 0, nullptr,
                                        0, nullptr, &enabled};
    vkCheck(vkCreateDevice(physical, &deviceInfo, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, family, 0, &queue_);
    const VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                           VK_COMMAND_POOL_CREATE_TRANSIENT_BIT, family};
    vkCheck(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool_), "vkCreateCommandPool");
}

int VulkanContext::memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags wanted) const {
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return int(i);
    return -1;
}

VkFormatFeatureFlags VulkanContext::imageFeatures(VkFormat format) const {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physicalDevice_, format, &p);
    return p.optimalTilingFeatures;
}

VkCommandBuffer VulkanContext::begin() const {
    const VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool_,
                                          VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    VkCommandBuffer cmd;
    vkCheck(vkAllocateCommandBuffers(device_, &info, &cmd), "vkAllocateCommandBuffers");
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                         VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    vkCheck(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    return cmd;
}

void VulkanContext::finish(VkCommandBuffer cmd) const {
    vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    const VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
    VkFence fence;
    vkCheck(vkCreateFence(device_, &fenceInfo, nullptr, &fence), "vkCreateFence");
    const VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd, 0, nullptr};
    VkResult r = vkQueueSubmit(queue_, 1, &submit, fence);
    if (r == VK_SUCCESS) r = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(device_, fence, nullptr);
    vkFreeCommandBuffers(device_, pool_, 1, &cmd);
    vkCheck(r, "running the compute shader");
}

}  // namespace vri
