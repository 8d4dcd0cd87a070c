#pragma once
// How the caller asks for a volume to be read, as text the way a tool's command line or a Python
// keyword gives it: the layout of a headerless raw file, a VDB file's grid and an override of the
// spacing. The tools'
// --dims, --type, --byte-order, --header-bytes and --spacing (tools/common/raw_input_options.h) and the
// Python module's keywords of the same names are read here, so that both check them the same way.
#include <filesystem>
#include <optional>
#include <string>

#include "libvri/core/brick_volume.h"
#include "libvri/io/volume_io.h"

namespace vri {

struct VolumeReadOptions {
    std::string dims, type;                 // raw input: "X,Y,Z" and a voxel type; empty: not given
    std::optional<std::string> byteOrder;   // raw input: "little" or "big"
    std::optional<long long> headerBytes;   // raw input: bytes to skip at the start
    std::string spacing;                    // "X,Y,Z" overriding what the input says; empty: not given
    std::optional<std::string> grid;        // .vdb input: the grid to read (readVdb); none: the first scalar grid
};

// The raw layout the options ask for (nullopt when none is given and the file's name or header must
// tell); throws vri::Error naming the option that is wrong.
std::optional<RawLayout> requestedRawLayout(const std::filesystem::path& input, const VolumeReadOptions& options);

// readVolume(input, requestedRawLayout(...)), or readVdb(input, grid), with the spacing override applied.
Volume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options);
// The same volume kept as `storage` says: a .vdb through readVdb(input, grid, storage), straight into
// bricks when sparse; any other format is read dense and, for Sparse, converted (SparseVolume::fromDense,
// the dense copy freed once converted), for Auto kept dense.
LoadedVolume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options, VolumeStorage storage);

// The dims and voxel type of a volume whose bricks readBrick reads without the whole: a raw file (its name's or
// the options' layout), an Inviwo .dat's, a NRRD's or MetaImage's whose voxels vri keeps as stored, a TIFF
// stack of such pages; nullopt for a file a brick reads whole. Reads no voxel (a header; a TIFF stack's page
// directories, through the OpenImageIO module).
struct VolumeShape {
    glm::ivec3 dims{0};
    VoxelType type = VoxelType::UInt8;
};
std::optional<VolumeShape> brickedShape(const std::filesystem::path& input, const VolumeReadOptions& options = {});

// One brick of the volume (core/brick_volume.h) of a `counts` grid. A raw file is read by its rows of the
// brick's stored box alone, so that the memory is the brick's, and so are an Inviwo .dat's raw file and a NRRD
// or MetaImage whose voxels vri keeps as stored (uncompressed; uint8, uint16 or float32); a TIFF stack of such
// pages by its rows; any other format is read whole and cut. The normalisation range is `range` when given,
// else the type's for integers, else (float) the whole file's min..max: streamed a chunk (a TIFF page) at a
// time. Throws vri::Error naming the option or file at fault.
BrickVolume readBrick(const std::filesystem::path& input, const VolumeReadOptions& options, glm::ivec3 counts,
                      glm::ivec3 brick, const std::optional<ValueRange>& range);

}  // namespace vri
