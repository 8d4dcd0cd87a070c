#pragma once
// Private to the volume readers/writers: the per-format entry points that readVolume and
// writeVolume dispatch to, and the small text helpers the header formats share.
#include <cstdint>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/core/brick_grid.h"
#include "libvri/core/volume.h"
#include "libvri/io/oiio_module.h"
#include "libvri/io/stored_voxels.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri::detail {

// .nhdr: a detached header and NAME.raw beside it; .nrrd: the header with the data attached.
void writeNrrd(const std::filesystem::path& path, const Volume& volume);
Volume readTiffStack(const std::filesystem::path& path);  // .tif/.tiff: one page per z slice
// A TIFF stack's shape, every page checked as readTiffStack checks it; no voxel read.
TiffStackShape tiffStackShape(const std::filesystem::path& path);
// The voxels [box.lo, box.hi) of a TIFF stack kept as stored (keptAsStored), read a run of rows at a time: the
// memory is the box's and about 1 MiB.
Volume readTiffStackBox(const std::filesystem::path& path, const VoxelBox& box);
// The min..max of a float32 TIFF stack, read a page at a time; a NaN or infinity is named as rawValueRange
// names it (by `volumeName`, else the file).
ValueRange tiffStackValueRange(const std::filesystem::path& path, const std::string& volumeName = {});
// "SOURCE: voxel N (x X, y Y, z Z) is V: ...": voxel `at` of a volume of `dims`, N its index in x-fastest order.
std::string nonFiniteVoxel(glm::ivec3 at, glm::ivec3 dims, double value, const std::string& source);
// The value range of `box`, voxels whose first sits at `start` in a volume of `dims`, a NaN or infinity among them
// refused by its place in that volume (nonFiniteVoxel): the range scans that stream a file a box at a time.
ValueRange boxValueRange(const Volume& box, glm::ivec3 start, glm::ivec3 dims, const std::string& source);

void writeInviwoDat(const std::filesystem::path& path, const Volume& volume);

// Where a header format's voxels are and how they are stored.
struct VoxelData {
    glm::ivec3 dims{0, 0, 0};
    StoredType type = StoredType::UInt8;
    ByteOrder order = ByteOrder::Little;
    std::optional<std::uintmax_t> offset = 0;  // bytes before the first voxel; nullopt: the file's last bytes
    bool gzip = false;                         // deflated (gzip or zlib stream) from `offset` on
};
// What a header (NRRD, MetaImage, Inviwo .dat) says of its voxels: where they are (its data file, or itself)
// and how they are stored, and what it says of their place and values (absent: the reader's defaults).
struct HeaderVoxels {
    std::filesystem::path dataPath;
    VoxelData data;
    glm::dvec3 spacing{1.0, 1.0, 1.0};
    std::optional<glm::dvec3> origin;  // vri's: the box's corner
    std::optional<ValueRange> range;   // NRRD's vri_range, the .dat's DataRange
    std::string_view entry;            // what the header calls its data file, for messages
};
// Parse the header of `path` (.nhdr or .nrrd, detached or attached; .mhd or .mha, LOCAL data or not; .dat) as
// the readers do, with their messages; read no voxel.
HeaderVoxels nrrdVoxels(const std::filesystem::path& path);
HeaderVoxels metaImageVoxels(const std::filesystem::path& path);
HeaderVoxels inviwoDatVoxels(const std::filesystem::path& path);
// The one of those three that the extension of `path` names; nullopt for a file that is not a header.
std::optional<HeaderVoxels> headerVoxels(const std::filesystem::path& path);
// Throws "PATH: dimensions must be at least 1x1x1" or "... spacing must be positive and finite" for a raw layout.
void requireValidLayout(const std::filesystem::path& path, const RawLayout& layout);
// The volume `header` describes (`voxels`, its parse): its voxels read, its messages after the header's.
Volume readHeaderVoxels(const std::filesystem::path& header, const HeaderVoxels& voxels);

// Where `data`'s voxels lie in `path` and how many bytes they take, checked before anything is allocated, so
// that a mistyped --dims or header is an error, not a huge allocation.
struct StoredVoxels {
    std::uint64_t bytes;
    std::uintmax_t offset, fileBytes;  // offset: data.offset, or where the file's last `bytes` begin
    std::string layoutText;            // "DxHxW type", for messages
};
StoredVoxels storedVoxels(const std::filesystem::path& path, const VoxelData& data);

// The volume (voxel types converted as stored_voxels.h says) whose voxels `data` describes in `path`.
// Sizes are checked against the file and the byte limit before anything is allocated.
Volume readVoxelData(const std::filesystem::path& path, const VoxelData& data);

// Runs read(), the reading of a header's data `file`: its messages come after the header that names it,
// "HEADER: data file FILE: ..." (`entry`: what the header calls it; none added where the header holds its own
// data, `file` == `header`).
template <class Read>
decltype(auto) namingHeader(const std::filesystem::path& header, const std::filesystem::path& file, Read&& read,
                            std::string_view entry = "data file") {
    // The data file's message, whose file it names (itself, or the one its object comes from), after the header's.
    const auto named = [&](const Error& e) {
        const std::string what = e.what();
        return header.string() + ": " + std::string(entry) + " " +
               (what.starts_with(file.string() + ":") ? what : file.string() + ": " + what);
    };
    try {
        return read();
    } catch (const Error& e) {
        if (file == header) throw;
        throwLike(e, named(e));
    }
}

// Runs read(), the reading of `path`: an OutOfMemory or OverLimit (checked_size.h) that does not name the file
// gets its name in front, and a std::bad_alloc that no check explained (a library's own allocation) becomes
// "PATH: out of memory while reading it".
template <class Read>
decltype(auto) namingFileIfTooLarge(const std::filesystem::path& path, Read&& read) {
    const auto named = [&](const Error& e) { return path.string() + ": " + e.what(); };
    const auto names = [&](const Error& e) { return std::string_view(e.what()).starts_with(path.string() + ":"); };
    try {
        return read();
    } catch (const Error& e) {
        if (!isSizeRefusal(e) || names(e)) throw;
        throwLike(e, named(e));
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(path.string() + ": out of memory while reading it");
    }
}

// Throws "PATH: no such file" (or "is not a regular file") before a reader opens it.
void requireRegularFile(const std::filesystem::path& path);

// The file a header's data-file entry names: `value` itself when absolute, else relative to the header's folder.
std::filesystem::path dataFileNamedBy(const std::filesystem::path& headerPath, std::string_view value);
// The raw file written beside a header file: same directory and stem, extension .raw.
std::filesystem::path rawFileBeside(const std::filesystem::path& headerPath);
// The voxel bytes as a raw file in `order` holds them: a view of volume.bytes, or of `swapped` once
// filled with each voxel's bytes reversed. Throws, naming `path`, if the volume disagrees with its dims.
std::string_view rawBytes(const std::filesystem::path& path, const Volume& volume, ByteOrder order,
                          std::vector<std::byte>& swapped);

// One "Key: value" (.dat) or "Key = Value" (MetaImage) header line.
struct HeaderEntry {
    std::string key;  // as written, for messages
    std::string value;
    int line = 0;
};

std::string_view trim(std::string_view text);
std::string toLower(std::string_view text);
// Exactly `count` whitespace-separated numbers; throws Error("<where>: ...") otherwise.
std::vector<double> parseNumbers(std::string_view text, std::size_t count, const std::string& where);
// A whole number of bytes, read as an integer (never through a double: "1e30" is an error, not an
// overflowing cast); throws Error("<where>: ...") otherwise.
std::uintmax_t parseByteCount(std::string_view text, const std::string& where);
// "lo hi" with lo < hi: an empty or inverted range would map every value to one end of the transfer
// function (or divide by zero); throws Error("<where>: ...") otherwise.
ValueRange parseValueRange(std::string_view text, const std::string& where);

}  // namespace vri::detail
