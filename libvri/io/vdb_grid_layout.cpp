#include "libvri/io/vdb_grid_layout.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/vector_relational.hpp>

#include "libvri/util/error.h"

namespace vri::detail {

namespace {

constexpr const char* kVoxelTypeKey = "vri_voxel_type";
constexpr const char* kDimsKey = "vri_dims";

// OpenVDB's own test (math::isDiagonal): the off-diagonal magnitudes sum to at most 1e-15, which
// forgives the rounding of a transform composed from scale and translation.
bool isDiagonalWithPositiveScale(const glm::dmat3& m) {
    double offDiagonal = 0.0;
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) {
            if (column != row)
                offDiagonal += std::abs(m[column][row]);
            else if (!(m[column][row] > 0.0))
                return false;  // NaN too
        }
    return offDiagonal <= 1e-15;
}

std::string coordText(glm::ivec3 c) {
    return "(" + std::to_string(c.x) + "," + std::to_string(c.y) + "," + std::to_string(c.z) + ")";
}

}  // namespace

VdbVolumeLayout vdbVolumeLayout(const std::string& path, const VdbGridFacts& grid) {
    if (!grid.linearTransform || !isDiagonalWithPositiveScale(grid.linear))
        throw Error(path + ": " + grid.description +
                    " has a rotated, flipped or non-linear transform; only axis-aligned grids are supported");

    VdbVolumeLayout layout;
    const bool writtenByVri = grid.voxelTypeMeta && grid.dimsMeta;
    if (writtenByVri) {
        const int version = grid.formatVersionMeta.value_or(1);
        if (version != 1 && version != kVdbFormatVersion)
            throw Error(path + ": vri_format_version " + std::to_string(version) + " is not one this vri reads (1 or " +
                        std::to_string(kVdbFormatVersion) + ")");
        layout.indexAtVoxelCentres = version == kVdbFormatVersion;
        layout.type = parseVoxelType(*grid.voxelTypeMeta, path + ": " + kVoxelTypeKey);
        const glm::ivec3 d = *grid.dimsMeta;
        if (d.x < 1 || d.y < 1 || d.z < 1) throw Error(path + ": " + kDimsKey + " must be positive");
        layout.dims = d;
        // vri writes voxel (i,j,k) at index (i,j,k): every active voxel lies inside the dims.
        if (grid.activeMin && grid.activeMax &&
            (glm::any(glm::lessThan(*grid.activeMin, glm::ivec3(0))) ||
             glm::any(glm::greaterThanEqual(*grid.activeMax, d))))
            throw Error(path + ": " + kDimsKey + " " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                        std::to_string(d.z) + " does not contain the active voxels " + coordText(*grid.activeMin) +
                        ".." + coordText(*grid.activeMax));
        if (grid.rangeMeta) layout.range = ValueRange{grid.rangeMeta->x, grid.rangeMeta->y};
    } else {
        if (!grid.activeMin || !grid.activeMax) throw Error(path + ": " + grid.description + " has no active voxels");
        layout.boxMin = *grid.activeMin;
        for (int axis = 0; axis < 3; ++axis) {
            // In 64 bits: a box from -2^31 to 2^31 - 1 is 2^32 voxels wide, more than an int holds.
            const std::int64_t extent =
                std::int64_t{(*grid.activeMax)[axis]} - std::int64_t{(*grid.activeMin)[axis]} + 1;
            if (extent < 1 || extent > std::numeric_limits<int>::max())
                throw Error(path + ": " + grid.description + "'s active voxels span " + std::to_string(extent) +
                            " voxels along an axis, more than a volume can hold");
            layout.dims[axis] = static_cast<int>(extent);
        }
    }

    // Every voxel type lives in a FloatGrid since version 2 (float holds every uint8 and uint16 value
    // exactly); version 1 kept uint8 and uint16 in an Int32Grid. A grid not written by vri is read as
    // float32 from any scalar type.
    const VdbValueType expected = layout.type == VoxelType::Float32 || layout.indexAtVoxelCentres
                                      ? VdbValueType::Float
                                      : VdbValueType::Int32;
    const bool fits = !writtenByVri || grid.valueType == expected;
    if (!fits)
        throw Error(path + ": " + grid.description + " cannot hold " + std::string(voxelTypeName(layout.type)) +
                    " voxels as its metadata claim");
    return layout;
}

}  // namespace vri::detail
