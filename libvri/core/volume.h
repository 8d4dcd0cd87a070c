#pragma once
// A regular scalar volume kept in its native voxel type, x fastest, then y, then z.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/voxel_type.h"

namespace vri {

// The closed interval of raw values that the transfer function's normalised scalar s = 0..1 spans.
struct ValueRange {
    double lo = 0.0;
    double hi = 1.0;
    bool operator==(const ValueRange&) const = default;
};

// The range to normalise values with when the volume states none (`range`): the type's full range for
// integers; nullopt for float, whose data min..max is used (Volume and SparseVolume compute it).
std::optional<ValueRange> fixedNormalisationRange(VoxelType type, const std::optional<ValueRange>& range);

class Volume {
public:
    Volume() = default;
    // Zero-filled volume; throws vri::Error when a dimension is < 1 or the bytes exceed byteLimit()
    // (checked_size.h).
    Volume(glm::ivec3 dims, VoxelType type);

    glm::ivec3 dims{0, 0, 0};
    glm::dvec3 spacing{1.0, 1.0, 1.0};  // distance between neighbouring voxel samples, world units
    glm::dvec3 origin{0.0, 0.0, 0.0};   // world position of the bounding box's min corner
    VoxelType type = VoxelType::UInt8;
    // Range to normalise values with; when absent the type's full range (integers) or the data's
    // min..max (float) is used, see normalisationRange().
    std::optional<ValueRange> range;
    std::vector<std::byte> bytes;  // voxelCount() * voxelSize(type) bytes, native byte order

    std::size_t voxelCount() const;
    std::size_t byteCount() const { return voxelCount() * voxelSize(type); }
    std::size_t index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * dims.y + y) * dims.x + x;
    }
    template <class T> const T* data() const { return reinterpret_cast<const T*>(bytes.data()); }
    template <class T> T* data() { return reinterpret_cast<T*>(bytes.data()); }

    double value(int x, int y, int z) const;  // any type, as double; no bounds check
    ValueRange dataRange() const;             // min..max over all voxels
    ValueRange normalisationRange() const;
    bool operator==(const Volume&) const = default;
};

}  // namespace vri
