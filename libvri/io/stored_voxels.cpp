#include "libvri/io/stored_voxels.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri::detail {

namespace {

// Calls f(T{}) with T the C++ type of a stored type.
template <class F>
decltype(auto) dispatchStoredType(StoredType type, F&& f) {
    switch (type) {
    case StoredType::Int8: return f(std::int8_t{});
    case StoredType::UInt8: return f(std::uint8_t{});
    case StoredType::Int16: return f(std::int16_t{});
    case StoredType::UInt16: return f(std::uint16_t{});
    case StoredType::Int32: return f(std::int32_t{});
    case StoredType::UInt32: return f(std::uint32_t{});
    case StoredType::Float32: return f(float{});
    case StoredType::Float64: break;
    }
    return f(double{});
}

template <class T>
T loadVoxel(const char* bytes, bool swap) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, bytes, sizeof(T));
    if (swap) std::reverse(b, b + sizeof(T));
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
}

}  // namespace

std::size_t storedSize(StoredType type) {
    return dispatchStoredType(type, [](auto v) { return sizeof(v); });
}

std::string_view storedTypeName(StoredType type) {
    switch (type) {
    case StoredType::Int8: return "int8";
    case StoredType::UInt8: return "uint8";
    case StoredType::Int16: return "int16";
    case StoredType::UInt16: return "uint16";
    case StoredType::Int32: return "int32";
    case StoredType::UInt32: return "uint32";
    case StoredType::Float32: return "float32";
    case StoredType::Float64: break;
    }
    return "float64";
}

StoredType storedTypeOf(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return StoredType::UInt8;
    case VoxelType::UInt16: return StoredType::UInt16;
    case VoxelType::Float32: break;
    }
    return StoredType::Float32;
}

VoxelType volumeTypeFor(StoredType type) {
    if (type == StoredType::UInt8) return VoxelType::UInt8;
    if (type == StoredType::UInt16) return VoxelType::UInt16;
    return VoxelType::Float32;
}

bool keptAsStored(StoredType type) { return storedTypeOf(volumeTypeFor(type)) == type; }

Volume decodeVoxels(const std::string& source, glm::ivec3 dims, StoredType type, ByteOrder order,
                    std::string_view bytes) {
    Volume volume(dims, volumeTypeFor(type));
    const bool swap = order != nativeByteOrder();
    dispatchStoredType(type, [&](auto stored) {
        using S = decltype(stored);
        const std::size_t count = volume.voxelCount();
        if constexpr (std::is_same_v<S, std::uint8_t> || std::is_same_v<S, std::uint16_t> ||
                      std::is_same_v<S, float>) {
            S* out = volume.data<S>();
            for (std::size_t i = 0; i < count; ++i) out[i] = loadVoxel<S>(bytes.data() + i * sizeof(S), swap);
        } else {
            float* out = volume.data<float>();
            for (std::size_t i = 0; i < count; ++i) {
                const S value = loadVoxel<S>(bytes.data() + i * sizeof(S), swap);
                if constexpr (std::is_same_v<S, double>) {
                    // Casting a finite double beyond float's range is undefined; NaN and infinities pass
                    // through to requireUsableValues, which names them.
                    if (std::isfinite(value) && std::abs(value) > double(std::numeric_limits<float>::max()))
                        throw Error(source + ": float64 voxel " + std::to_string(i) + " is " + exactNumber(value) +
                                    ", beyond float32's range (float64 volumes are kept as float32)");
                }
                out[i] = static_cast<float>(value);
            }
            if constexpr (std::is_integral_v<S>)
                volume.range = ValueRange{double(std::numeric_limits<S>::min()), double(std::numeric_limits<S>::max())};
        }
    });
    return volume;
}

}  // namespace vri::detail
