#include "libvri/core/voxel_type.h"

#include <algorithm>
#include <bit>
#include <cctype>

#include "libvri/util/error.h"

namespace vri {

std::size_t voxelSize(VoxelType type) {
    return dispatchVoxelType(type, [](auto v) { return sizeof(v); });
}

std::string_view voxelTypeName(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Float32: break;
    }
    return "float32";
}

VoxelType parseVoxelType(std::string_view name, const std::string& what) {
    std::string n(name);
    std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return std::tolower(c); });
    if (n == "uint8" || n == "uchar" || n == "unsigned char" || n == "uint8_t" || n == "u8")
        return VoxelType::UInt8;
    if (n == "uint16" || n == "ushort" || n == "unsigned short" || n == "uint16_t" || n == "u16")
        return VoxelType::UInt16;
    if (n == "float32" || n == "float" || n == "f32")
        return VoxelType::Float32;
    throw Error(what + ": unknown voxel type '" + std::string(name) +
                "' (expected uint8, uint16 or float32)");
}

ByteOrder nativeByteOrder() {
    return std::endian::native == std::endian::little ? ByteOrder::Little : ByteOrder::Big;
}

}  // namespace vri
