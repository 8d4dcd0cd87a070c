#pragma once
// The render options that choose a backend, named here below both backends so that the experiment
// reader and the tools can read and check them without the Vulkan backend being built.
#include <string>
#include <string_view>

namespace vri {

// Which renderer draws: vri::render() on the CPU, or VulkanRenderer.
enum class Backend { Cpu, Vulkan };
Backend parseBackend(std::string_view name, const std::string& what);  // "cpu", "vulkan"

// Where the volume is interpolated. Shader (the default) reads the voxels from a storage buffer and
// interpolates with grid_sampler.h's formula in float. Sampler uploads a 3D image (R8 or R16 unorm, R32
// float) and lets the texture unit filter it, with the weights' precision the device chooses: 8
// fractional bits on many GPUs, which the sampler experiment measures against the shader.
enum class VulkanInterpolation { Shader, Sampler };
std::string_view interpolationName(VulkanInterpolation i);  // "shader", "sampler"
VulkanInterpolation parseInterpolation(std::string_view name, const std::string& what);

}  // namespace vri
