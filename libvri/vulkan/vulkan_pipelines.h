#pragma once
// Compute shaders that share one descriptor set: its layout, the set itself, the shader modules and
// their pipelines (one per combination of specialisation constants), and a dispatch that waits for
// the device. What vulkan_renderer.cpp and vulkan_sampler_probe.cpp both run on. Private to libvri.
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

namespace vri {

class VulkanBuffer;
class VulkanContext;
class VulkanTexture3D;

class VulkanPipelines {
public:
    // Binding i of the set has descriptor type bindings[i].
    VulkanPipelines(const VulkanContext& context, std::vector<VkDescriptorType> bindings);
    ~VulkanPipelines();
    VulkanPipelines(const VulkanPipelines&) = delete;
    VulkanPipelines& operator=(const VulkanPipelines&) = delete;

    // A shader module of SPIR-V words (a glslangValidator --vn array), kept until destruction.
    VkShaderModule module(const std::uint32_t* code, std::size_t bytes);
    // The pipeline of `module` with specialisation constants 0, 1, ... = `constants`, created once.
    VkPipeline pipeline(VkShaderModule module, const std::vector<int>& constants = {});

    void bind(std::uint32_t binding, const VulkanBuffer& buffer) const;
    void bind(std::uint32_t binding, const VulkanTexture3D& texture) const;

    // Runs `pipeline` on groups x groups y work groups, waits, and makes its writes visible to the host.
    void dispatch(VkPipeline pipeline, std::uint32_t groupsX, std::uint32_t groupsY) const;

private:
    const VulkanContext& context_;
    std::vector<VkDescriptorType> bindings_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::vector<VkShaderModule> modules_;
    std::map<std::pair<VkShaderModule, std::vector<int>>, VkPipeline> pipelines_;
};

}  // namespace vri
