#include "libvri/vulkan/vulkan_sampler_probe.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "libvri/vulkan/vulkan_context.h"
#include "libvri/vulkan/vulkan_pipelines.h"
#include "libvri/vulkan/vulkan_texture.h"

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

}  // namespace

double SamplerProbe::effectiveBits() const {
    return maxError > 0.0 ? -std::log2(maxError) : std::numeric_limits<double>::infinity();
}

SamplerProbe probeSampler(const VulkanContext& context, VoxelType type) {
    const VolumeTextureFormat f = volumeTextureFormat(type);
    const std::vector<std::uint8_t> texels = probeTexels(type);
    const VulkanTexture3D texture(context, {2, 1, 1}, f.format, f.name, texels.data(), texels.size());
    const VulkanBuffer read(context, kPoints * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    VulkanPipelines probe(context, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
    probe.bind(0, texture);
    probe.bind(1, read);
    probe.dispatch(probe.pipeline(probe.module(sampler_probe_spv, sizeof(sampler_probe_spv))), (kPoints + 63) / 64, 1);
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
