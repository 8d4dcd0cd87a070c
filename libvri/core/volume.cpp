#include "libvri/core/volume.h"

#include <algorithm>
#include <limits>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri {

Volume::Volume(glm::ivec3 d, VoxelType t) : dims(d), type(t) {
    if (d.x < 1 || d.y < 1 || d.z < 1)
        throw Error("volume dimensions must be at least 1x1x1, got " + std::to_string(d.x) + "x" +
                    std::to_string(d.y) + "x" + std::to_string(d.z));
    // Checked before voxelCount() multiplies in size_t, where 2097152 x 2097152 x 4194304 wraps to 0.
    const std::string what = "a " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z) +
                             " " + std::string(voxelTypeName(t)) + " volume";
    const std::size_t size =
        checkedBytes(what, {std::uint64_t(d.x), std::uint64_t(d.y), std::uint64_t(d.z), voxelSize(t)});
    allocateOrExplain(what, size, [&] { bytes.assign(size, std::byte{0}); });
}

std::size_t Volume::voxelCount() const {
    return static_cast<std::size_t>(std::max(dims.x, 0)) * std::max(dims.y, 0) * std::max(dims.z, 0);
}

double Volume::value(int x, int y, int z) const {
    return dispatchVoxelType(type, [&](auto t) {
        return static_cast<double>(data<decltype(t)>()[index(x, y, z)]);
    });
}

ValueRange Volume::dataRange() const {
    return dispatchVoxelType(type, [&](auto t) {
        using T = decltype(t);
        const T* p = data<T>();
        const std::size_t n = voxelCount();
        if (n == 0) return ValueRange{0.0, 0.0};
        auto [lo, hi] = std::minmax_element(p, p + n);
        return ValueRange{static_cast<double>(*lo), static_cast<double>(*hi)};
    });
}

std::optional<ValueRange> fixedNormalisationRange(VoxelType type, const std::optional<ValueRange>& range) {
    if (range) return range;
    switch (type) {
    case VoxelType::UInt8: return ValueRange{0.0, 255.0};
    case VoxelType::UInt16: return ValueRange{0.0, 65535.0};
    case VoxelType::Float32: break;
    }
    return std::nullopt;
}

ValueRange Volume::normalisationRange() const {
    const std::optional<ValueRange> fixed = fixedNormalisationRange(type, range);
    return fixed ? *fixed : dataRange();
}

}  // namespace vri
