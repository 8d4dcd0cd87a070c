#include "vulkan_sampler_probe.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "vulkan_context.h"
#include "vulkan_texture.h"

// SPIR-V of shaders/sampler_probe.comp (libvri/CMakeLists.txt).
#include "sampler_probe_spv.h"

namespace vri {

namespace {

constexpr std::uint32_t kPoints = 4097;  // sampler_probe.comp's COUNT: 4096 intervals keep every coordinate exact

// The 2x1x1 image: 0 and full scale in the type's native bytes.
std::vector<std::uint8_t> probeTexels(VoxelType type) {
    std::vector<std::uint8_t> bytes(2 * voxelSize(type), 0);
    switch (type) {
    case VoxelType::UInt8: bytes[1] = 0xff; break;
    case VoxelType::UInt16: bytes[2] = bytes[3] = 0xff; break;
    case VoxelType::Float32: {
        const float one = 1.0f;
        std::memcpy(bytes.data() + 4, &one, 4);
        break;
    }
    }
    return bytes;
}

// The probe's Vulkan objects, destroyed in reverse order of creation.
struct ProbePipeline {
    VkDevice device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;

    explicit ProbePipeline(VkDevice d) : device(d) {
        const VkDescriptorSetLayoutBinding bindings[] = {
            {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
            {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
        const VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0, 2,
                                                      bindings};
        vkCheck(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
        const VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1,
                                                    &setLayout, 0, nullptr};
        vkCheck(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                              {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
        const VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1, 2, sizes};
        vkCheck(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
        const VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool, 1,
                                                    &setLayout};
        vkCheck(vkAllocateDescriptorSets(device, &allocInfo, &set), "vkAllocateDescriptorSets");
        const VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0,
                                                  sizeof(sampler_probe_spv), sampler_probe_spv};
        vkCheck(vkCreateShaderModule(device, &moduleInfo, nullptr, &module), "vkCreateShaderModule");
        const VkComputePipelineCreateInfo pipelineInfo{
            VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
            nullptr,
            0,
            {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main",
             nullptr},
            layout,
            VK_NULL_HANDLE,
            -1};
        vkCheck(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline),
                "vkCreateComputePipelines");
    }

    ~ProbePipeline() {
        if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
        if (module) vkDestroyShaderModule(device, module, nullptr);
        if (pool) vkDestroyDescriptorPool(device, pool, nullptr);
        if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
        if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    }
    ProbePipeline(const ProbePipeline&) = delete;
    ProbePipeline& operator=(const ProbePipeline&) = delete;
};

}  // namespace

double SamplerProbe::effectiveBits() const {
    return maxError > 0.0 ? -std::log2(maxError) : std::numeric_limits<double>::infinity();
}

SamplerProbe probeSampler(const VulkanContext& context, VoxelType type) {
    const VolumeTextureFormat f = volumeTextureFormat(type);
    const std::vector<std::uint8_t> texels = probeTexels(type);
    const VulkanTexture3D texture(context, {2, 1, 1}, f.format, f.name, texels.data(), texels.size());
    const VulkanBuffer read(context, kPoints * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    const ProbePipeline probe(context.device());

    const VkDescriptorImageInfo image{texture.sampler(), texture.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorBufferInfo buffer{read.handle(), 0, VK_WHOLE_SIZE};
    const VkWriteDescriptorSet writes[] = {
        {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, probe.set, 0, 0, 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
         &image, nullptr, nullptr},
        {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, probe.set, 1, 0, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr,
         &buffer, nullptr}};
    vkUpdateDescriptorSets(context.device(), 2, writes, 0, nullptr);
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, probe.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, probe.layout, 0, 1, &probe.set, 0, nullptr);
        vkCmdDispatch(cmd, (kPoints + 63) / 64, 1, 1);
        const VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                                     VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                             nullptr, 0, nullptr);
    });
    read.invalidate();

    SamplerProbe out;
    out.format = f.name;
    out.subTexelPrecisionBits = int(context.properties().limits.subTexelPrecisionBits);
    const auto* values = static_cast<const float*>(read.mapped());
    for (std::uint32_t i = 0; i < kPoints; ++i) {
        out.weight.push_back(double(i) / double(kPoints - 1));
        out.read.push_back(values[i]);
        out.maxError = std::max(out.maxError, std::abs(out.read.back() - out.weight.back()));
    }
    return out;
}

}  // namespace vri
