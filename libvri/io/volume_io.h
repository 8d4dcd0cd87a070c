#pragma once
// Reading and writing volumes: headerless raw files, NRRD (.nhdr/.nrrd), Inviwo .dat, OpenVDB .vdb and
// (read only) MetaImage .mhd/.mha and TIFF stacks. README.md's "formats" table says what each holds and where its voxels sit.
// Every failure is a vri::Error whose one-line message starts with the offending file's path.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/brick_grid.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/core/volume.h"
#include "libvri/core/voxel_type.h"

namespace vri {

// How the voxels of a headerless raw file are laid out (x fastest, then y, then z).
struct RawLayout {
    glm::ivec3 dims{0, 0, 0};
    VoxelType type = VoxelType::UInt8;
    ByteOrder order = ByteOrder::Little;
    glm::dvec3 spacing{1.0, 1.0, 1.0};
    std::size_t headerBytes = 0;  // bytes to skip before the first voxel
};

// Reads a raw file whose size must be exactly headerBytes + voxel count * voxel size.
Volume readRaw(const std::filesystem::path& path, const RawLayout& layout);
// The voxels [box.lo, box.hi) of a raw file whose size must be as readRaw's, read row by row from their
// offsets: the memory is the box's, whatever the file's size (a brick, core/brick_volume.h).
Volume readRawBox(const std::filesystem::path& path, const RawLayout& layout, const VoxelBox& box);
// The min..max of a raw file's voxels, read a chunk at a time; throws vri::Error at a NaN or an infinity
// (float) as requireUsableValues would on the whole volume, naming `volumeName` (the header that describes the
// file), else the file.
ValueRange rawValueRange(const std::filesystem::path& path, const RawLayout& layout,
                         const std::string& volumeName = {});
// Writes the voxels only (no header), atomically.
void writeRaw(const std::filesystem::path& path, const Volume& volume, ByteOrder order = ByteOrder::Little);

// The Open SciVis naming convention NAME_XxYxZ_TYPE.raw (little endian, unit spacing).
// Returns nullopt when the name does not follow it; throws when it does but names a voxel
// type that vri does not support (e.g. float64).
std::optional<RawLayout> layoutFromFileName(const std::filesystem::path& path);

// Throws vri::Error "<source>: ..." unless every float voxel is finite, the range (when set) is a finite
// lo < hi and the box, origin + dims x spacing, stays within double's range along every axis.
void requireUsableValues(const Volume& volume, const std::string& source);
void requireUsableValues(const SparseVolume& volume, const std::string& source);
// The same for the stored box of a brick of a volume of `dims` (core/brick_volume.h): a voxel named by its place
// in the whole volume, and the whole volume's box checked, so that a brick refuses what the whole would.
void requireUsableValues(const Volume& box, const VoxelBox& stored, glm::ivec3 dims, const std::string& source);
// The part of those checks that is not the voxels: the range (when set) and the box of a volume of `dims`.
void requireUsableGeometry(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 origin,
                           const std::optional<ValueRange>& range, const std::string& source);

// How a volume is kept in memory: dense (Volume), sparse (SparseVolume: the 8^3 bricks that are not all
// background), or auto: sparse for a .vdb whose dense box would be refused (over the byte limit, or over
// the plausible size for its file, see readVdb), dense otherwise.
enum class VolumeStorage { Dense, Sparse, Auto };
VolumeStorage parseVolumeStorage(std::string_view name, const std::string& what);  // "dense", "sparse", "auto"
std::string_view volumeStorageName(VolumeStorage storage);
// A volume as read: exactly one of the two is set.
struct LoadedVolume {
    std::shared_ptr<Volume> dense;
    std::shared_ptr<SparseVolume> sparse;
};

// True for the formats whose files say their own layout (by extension: .nhdr/.nrrd, .dat, .vdb, .mhd/.mha,
// .tif/.tiff); any other file is raw.
bool describesItsLayout(const std::filesystem::path& path);
// The layout a raw file is read with: `requested`, else its name's (layoutFromFileName); nullopt for a file
// that describes its own layout. Throws vri::Error naming the file for a layout given to such a file, or a
// raw file whose layout is neither given nor in its name.
std::optional<RawLayout> rawLayoutOf(const std::filesystem::path& path, const std::optional<RawLayout>& requested);
// Reads any supported format, chosen by extension: .nhdr/.nrrd, .dat (Inviwo), .vdb, .mhd/.mha, .tif/.tiff;
// anything
// else is raw, laid out by `rawLayout` if given, else by layoutFromFileName.
// The volume read passes requireUsableValues.
Volume readVolume(const std::filesystem::path& path, const std::optional<RawLayout>& rawLayout = {});
// Writes by extension: .vdb, .nhdr (header + NAME.raw beside it), .nrrd (data attached), .dat (+ NAME.raw),
// .raw (little endian),
// through atomic_file.h; a header and its raw file are written together (neither replaced if one fails).
void writeVolume(const std::filesystem::path& path, const Volume& volume);
// The files writeVolume(path, ...) creates or replaces: `path`, and for .nhdr and .dat the raw
// file beside it. A tool checks them against its input before it overwrites what it reads.
std::vector<std::filesystem::path> filesWrittenBy(const std::filesystem::path& path);
// The files readVolume(path) reads: `path`, and the data file a header names (NRRD `data file`,
// MetaImage ElementDataFile, Inviwo .dat Rawfile). A tool checks its outputs against them before it
// writes (an output onto an input's data file would destroy what the header describes).
std::vector<std::filesystem::path> filesReadBy(const std::filesystem::path& path);

// OpenVDB. Volumes written by writeVdb come back with their type, voxel values (bit for bit), dims, spacing
// and range; the origin is kept as the first voxel's centre, origin + spacing / 2, exact whenever that sum
// is. For other .vdb files the first float, double, int32 or int64 grid (or the one named `gridName`) is
// read as float32 over its active voxels' bounding box, index (i,j,k) the centre of a cell-centred voxel.
Volume readVdb(const std::filesystem::path& path, const std::optional<std::string>& gridName = {});
// The same grid kept as `storage` says. Sparse: only the bricks that a leaf node or a tile of another value
// than the background overlaps are read (never the dense box), the background is the grid's; the brick
// table (4 bytes per 8^3 voxels of the box) is checked as a dense volume is (the byte limit and, unless
// VRI_MAX_BYTES is set, the file's size), and so are the bricks kept (the byte limit).
LoadedVolume readVdb(const std::filesystem::path& path, const std::optional<std::string>& gridName,
                     VolumeStorage storage);
void writeVdb(const std::filesystem::path& path, const Volume& volume);

}  // namespace vri
