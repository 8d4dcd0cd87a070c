#include "libvri/vulkan/vulkan_pipelines.h"

#include "libvri/vulkan/vulkan_context.h"
#include "libvri/vulkan/vulkan_texture.h"

namespace vri {

VulkanPipelines::VulkanPipelines(const VulkanContext& context, std::vector<VkDescriptorType> bindings)
    : context_(context), bindings_(std::move(bindings)) {
    const VkDevice device = context_.device();
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    std::map<VkDescriptorType, std::uint32_t> counts;
    for (std::uint32_t b = 0; b < bindings_.size(); ++b) {
        layoutBindings.push_back({b, bindings_[b], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
        ++counts[bindings_[b]];
    }
    const VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0,
                                                  std::uint32_t(layoutBindings.size()), layoutBindings.data()};
    vkCheck(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
    const VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1,
                                                &setLayout_, 0, nullptr};
    vkCheck(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout_), "vkCreatePipelineLayout");
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : counts) sizes.push_back({type, count});
    const VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1,
                                              std::uint32_t(sizes.size()), sizes.data()};
    vkCheck(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool");
    const VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool_, 1,
                                                &setLayout_};
    vkCheck(vkAllocateDescriptorSets(device, &allocInfo, &set_), "vkAllocateDescriptorSets");
}

VulkanPipelines::~VulkanPipelines() {
    const VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    for (const auto& [key, pipeline] : pipelines_) vkDestroyPipeline(device, pipeline, nullptr);
    for (VkShaderModule m : modules_) vkDestroyShaderModule(device, m, nullptr);
    vkDestroyDescriptorPool(device, pool_, nullptr);  // frees the set
    vkDestroyPipelineLayout(device, layout_, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
}

VkShaderModule VulkanPipelines::module(const std::uint32_t* code, std::size_t bytes) {
    const VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, bytes, code};
    VkShaderModule m;
    vkCheck(vkCreateShaderModule(context_.device(), &info, nullptr, &m), "vkCreateShaderModule");
    modules_.push_back(m);
    return m;
}

VkPipeline VulkanPipelines::pipeline(VkShaderModule module, const std::vector<int>& constants) {
    auto key = std::pair{module, constants};
    if (const auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < constants.size(); ++i) entries.push_back({i, i * 4u, 4u});
    const VkSpecializationInfo spec{std::uint32_t(entries.size()), entries.data(), constants.size() * sizeof(int),
                                    constants.data()};
    const VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                                                VK_SHADER_STAGE_COMPUTE_BIT, module, "main", &spec};
    const VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, nullptr, 0, stage, layout_,
                                           VK_NULL_HANDLE, -1};
    VkPipeline p;
    vkCheck(vkCreateComputePipelines(context_.device(), VK_NULL_HANDLE, 1, &info, nullptr, &p),
            "vkCreateComputePipelines");
    return pipelines_[std::move(key)] = p;
}

void VulkanPipelines::bind(std::uint32_t binding, const VulkanBuffer& buffer) const {
    const VkDescriptorBufferInfo info{buffer.handle(), 0, VK_WHOLE_SIZE};
    const VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set_, binding, 0, 1,
                                     bindings_.at(binding), nullptr, &info, nullptr};
    vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
}

void VulkanPipelines::bind(std::uint32_t binding, const VulkanTexture3D& texture) const {
    const VkDescriptorImageInfo info{texture.sampler(), texture.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set_, binding, 0, 1,
                                     bindings_.at(binding), &info, nullptr, nullptr};
    vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
}

void VulkanPipelines::dispatch(VkPipeline pipeline, std::uint32_t groupsX, std::uint32_t groupsY) const {
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
        vkCmdDispatch(cmd, groupsX, groupsY, 1);
        const VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                                     VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                             nullptr, 0, nullptr);
    });
}

}  // namespace vri
