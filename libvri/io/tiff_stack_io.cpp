// TIFF stacks, read by vri's OpenImageIO module (oiio_module.h): a multi-page TIFF whose pages (subimages)
// are the z slices, each one channel of the same width and height. Pixel (x, row) of page z is voxel
// (x, y = row, z): the first row, which viewers show at the top, is y = 0. TIFF says nothing vri can use
// about the spacing between pages, so the volume has unit spacing and its box corner at 0 (--spacing sets
// the spacing).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "libvri/io/io_module.h"
#include "libvri/io/oiio_module.h"
#include "libvri/io/tiff_page_chain.h"
#include "libvri/io/volume_formats.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// "PATH: WxHxD TYPE" for a box of `dims` of the stack: what messages about its sizes begin with.
std::string describe(const fs::path& path, glm::ivec3 dims, StoredType type) {
    return path.string() + ": " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) +
           " " + std::string(storedTypeName(type));
}

// The bytes of a box of `dims` of the stack, checked against what the file's size plausibly holds (pages may
// be compressed: deflate, LZW, PackBits) and against the byte limit.
std::size_t checkedBoxBytes(const fs::path& path, glm::ivec3 dims, StoredType type) {
    return checkedUnpackedBytes(describe(path, dims, type),
                                {std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z), storedSize(type)},
                                fs::file_size(path), "a file", kPlausibleCompressedExpansion);
}

// Reads what `read` asks of the stack once its shape is checked: its pages counted by the file's own chain
// too. Each `allocate` checks the bytes it allocates (checkedBoxBytes) and, besides, what the module holds:
// a run of whole rows, at most one row over 1 MiB.
void readChecked(const fs::path& path, TiffStackRead read) {
    requireRegularFile(path);
    const int chainedPages = tiffPageCount(path);
    read.allocate = [&, allocate = std::move(read.allocate)](const TiffStackShape& shape) -> char* {
        if (shape.pages != chainedPages)
            throw Error(path.string() + ": page " + std::to_string(shape.pages) + " cannot be read, the file chains " +
                        std::to_string(chainedPages) + " pages");
        if (shape.width < 1 || shape.height < 1)
            throw Error(path.string() + ": pages of " + std::to_string(shape.width) + "x" +
                        std::to_string(shape.height) + " pixels");
        return allocate(shape);
    };
    requireModuleSuccess(oiioModule(path, "read a TIFF stack").readTiffStack(path, read));
}

glm::ivec3 dimsOf(const TiffStackShape& shape) { return {shape.width, shape.height, shape.pages}; }

}  // namespace

Volume readTiffStack(const fs::path& path) {
    glm::ivec3 dims(0);
    StoredType type = StoredType::UInt8;
    // Not zero-filled (new char[], not a string): a page takes memory once OpenImageIO has read it, so that
    // pages a file claims but does not hold cost nothing before the read of the first of them fails.
    std::unique_ptr<char[]> voxels;
    std::size_t voxelBytes = 0;
    readChecked(path, {std::nullopt,
                       [&](const TiffStackShape& shape) {
                           dims = dimsOf(shape);
                           type = shape.type;
                           voxelBytes = checkedBoxBytes(path, dims, type);
                           allocateOrExplain(describe(path, dims, type), voxelBytes,
                                             [&] { voxels.reset(new char[voxelBytes]); });
                           return voxels.get();
                       },
                       {}});
    return decodeVoxels(path.string(), dims, type, nativeByteOrder(), {voxels.get(), voxelBytes});
}

TiffStackShape tiffStackShape(const fs::path& path) {
    TiffStackShape found;
    readChecked(path, {std::nullopt,
                       [&](const TiffStackShape& shape) -> char* {
                           found = shape;
                           return nullptr;
                       },
                       {}});
    return found;
}

Volume readTiffStackBox(const fs::path& path, const VoxelBox& box) {
    Volume volume;
    readChecked(path, {box,
                       [&](const TiffStackShape& shape) {
                           if (!keptAsStored(shape.type))
                               throw Error(path.string() + ": a box of a " + std::string(storedTypeName(shape.type)) +
                                           " stack is read with the whole stack (its voxels are converted)");
                           checkedBoxBytes(path, box.size(), shape.type);
                           checkedBoxBytes(path, {shape.width, 1, 1}, shape.type);  // a row of the module's run
                           volume = namingFileIfTooLarge(path,
                                                         [&] { return Volume(box.size(), volumeTypeFor(shape.type)); });
                           return reinterpret_cast<char*>(volume.bytes.data());
                       },
                       {}});
    return volume;
}

ValueRange tiffStackValueRange(const fs::path& path, const std::string& volumeName) {
    ValueRange range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    Volume page;
    glm::ivec3 dims(0);
    readChecked(
        path,
        {std::nullopt,
         [&](const TiffStackShape& shape) {
             if (shape.type != StoredType::Float32)
                 throw Error(path.string() + ": the value range is scanned for float stacks only");
             dims = dimsOf(shape);
             checkedBoxBytes(path, {dims.x, dims.y, 1}, shape.type);
             page = namingFileIfTooLarge(path, [&] { return Volume({dims.x, dims.y, 1}, VoxelType::Float32); });
             return reinterpret_cast<char*>(page.bytes.data());
         },
         [&](int z) {
             const ValueRange r = boxValueRange(page, {0, 0, z}, dims, volumeName.empty() ? path.string() : volumeName);
             range.lo = std::min(range.lo, r.lo);
             range.hi = std::max(range.hi, r.hi);
         }});
    return range;
}

}  // namespace vri::detail
