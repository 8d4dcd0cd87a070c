#pragma once
// Private to the .vdb reader: what a grid's metadata and transform mean as a vri volume. The decision is
// made from plain values that the OpenVDB module (vdb/vdb_grids.cpp) reads off the grid, so that it can be
// tested and fuzzed (tests/fuzz/fuzz_vdb_metadata.cpp) without OpenVDB or a .vdb file.
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "libvri/core/volume.h"
#include "libvri/core/voxel_type.h"

namespace vri::detail {

// The scalar grid types the reader accepts. A FloatGrid saved with half-float compression on disk is a
// FloatGrid once read.
enum class VdbValueType { Float, Double, Int32, Int64 };

// vri_format_version of the grids vri writes now: a FloatGrid whose index (i,j,k) is voxel (i,j,k)'s
// centre, as OpenVDB and the programs that read it assume. Grids with vri's metadata but no version
// are the earlier layout: uint8/uint16 in an Int32Grid, index (0,0,0) at the box's corner.
inline constexpr int kVdbFormatVersion = 2;

// What is known about a grid before any voxel is copied.
struct VdbGridFacts {
    std::string description;  // "grid 'density' (float)", for messages
    VdbValueType valueType = VdbValueType::Float;
    bool linearTransform = true;
    glm::dmat3 linear{1.0};                    // the linear part of the index-to-world map; [column][row] as in GLM
    std::optional<std::string> voxelTypeMeta;  // vri_voxel_type
    std::optional<glm::ivec3> dimsMeta;        // vri_dims
    std::optional<glm::dvec2> rangeMeta;       // vri_range
    std::optional<int> formatVersionMeta;      // vri_format_version
    // The active voxels' bounding box, min and max inclusive; nullopt when no voxel is active.
    std::optional<glm::ivec3> activeMin, activeMax;
};

// The dense index box [boxMin, boxMin + dims) that becomes the volume, and what its voxels are.
struct VdbVolumeLayout {
    glm::ivec3 boxMin{0, 0, 0};
    glm::ivec3 dims{0, 0, 0};
    VoxelType type = VoxelType::Float32;
    std::optional<ValueRange> range;
    // Whether index (i,j,k) maps to the voxel's centre (OpenVDB's meaning, and vri's since format
    // version 2; the box corner is then half a voxel below index boxMin) or to the box corner (version 1).
    bool indexAtVoxelCentres = true;
};

// Grids written by vri (both vri_voxel_type and vri_dims present) come back with their type, dense dims
// and range; any other grid is read as float32 over its active voxels. Throws vri::Error "<path>: ..."
// for a rotated, flipped or non-linear transform, metadata that do not fit the grid (its value type, an
// unknown vri_format_version, or active voxels outside vri_dims), or an empty grid.
VdbVolumeLayout vdbVolumeLayout(const std::string& path, const VdbGridFacts& grid);

}  // namespace vri::detail
