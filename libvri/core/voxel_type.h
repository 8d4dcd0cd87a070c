#pragma once
// The voxel types a volume may be stored in. Data stay in their native type in memory;
// only the sampler converts to floating point.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

namespace vri {

enum class VoxelType { UInt8, UInt16, Float32 };

std::size_t voxelSize(VoxelType type);
std::string_view voxelTypeName(VoxelType type);  // "uint8", "uint16", "float32"
// Accepts our names and the usual aliases (uchar, ushort, float, UINT8, ...); throws vri::Error
// naming `what` (a file or argument) when the name is unknown.
VoxelType parseVoxelType(std::string_view name, const std::string& what);

enum class ByteOrder { Little, Big };
ByteOrder nativeByteOrder();

// Calls f(T{}) with T the C++ type of `type`: the one place where a runtime type becomes a template.
template <class F>
decltype(auto) dispatchVoxelType(VoxelType type, F&& f) {
    switch (type) {
    case VoxelType::UInt8: return f(std::uint8_t{});
    case VoxelType::UInt16: return f(std::uint16_t{});
    case VoxelType::Float32: break;
    }
    return f(float{});
}

// The VoxelType of the C++ type T: dispatchVoxelType's inverse.
template <class T>
constexpr VoxelType voxelTypeOf() {
    static_assert(std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::uint16_t> || std::is_same_v<T, float>);
    return std::is_same_v<T, std::uint8_t> ? VoxelType::UInt8 : std::is_same_v<T, std::uint16_t> ? VoxelType::UInt16
                                                                                                 : VoxelType::Float32;
}

}  // namespace vri
