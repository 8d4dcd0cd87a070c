// TIFF stacks, read by vri's OpenImageIO module (oiio_module.h): a multi-page TIFF whose pages (subimages)
// are the z slices, each one channel of the same width and height. Pixel (x, row) of page z is voxel
// (x, y = row, z): the first row, which viewers show at the top, is y = 0. TIFF says nothing vri can use
// about the spacing between pages, so the volume has unit spacing and its box corner at 0 (--spacing sets
// the spacing).
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

Volume readTiffStack(const fs::path& path) {
    requireRegularFile(path);
    const int chainedPages = tiffPageCount(path);
    glm::ivec3 dims(0);
    StoredType type = StoredType::UInt8;
    // Not zero-filled (new char[], not a string): a page takes memory once OpenImageIO has read it, so that
    // pages a file claims but does not hold cost nothing before the read of the first of them fails.
    std::unique_ptr<char[]> voxels;
    std::size_t voxelBytes = 0;
    const auto allocate = [&](const TiffStackShape& shape) {
        if (shape.pages != chainedPages)
            throw Error(path.string() + ": page " + std::to_string(shape.pages) + " cannot be read, the file chains " +
                        std::to_string(chainedPages) + " pages");
        dims = glm::ivec3(shape.width, shape.height, shape.pages);
        type = shape.type;
        if (dims.x < 1 || dims.y < 1)
            throw Error(path.string() + ": pages of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                        " pixels");
        // Pages may be compressed (deflate, LZW, PackBits): the file's size bounds what they plausibly hold.
        const std::string what = path.string() + ": " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                 std::to_string(dims.z) + " " + std::string(storedTypeName(type));
        voxelBytes = checkedUnpackedBytes(
            what, {std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z), storedSize(type)},
            fs::file_size(path), "a file", kPlausibleCompressedExpansion);
        allocateOrExplain(what, voxelBytes, [&] { voxels.reset(new char[voxelBytes]); });
        return voxels.get();
    };
    requireModuleSuccess(oiioModule(path, "read a TIFF stack").readTiffStack(path, allocate));
    return decodeVoxels(path.string(), dims, type, nativeByteOrder(), {voxels.get(), voxelBytes});
}

}  // namespace vri::detail
