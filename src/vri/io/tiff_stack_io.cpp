// TIFF stacks through OpenImageIO: a multi-page TIFF whose pages (subimages) are the z slices, each one
// channel of the same width and height. Pixel (x, row) of page z is voxel (x, y = row, z): the first
// row, which viewers show at the top, is y = 0. TIFF says nothing vri can use about the spacing between
// pages, so the volume has unit spacing and its box corner at 0 (--spacing sets the spacing).
#include <cstring>
#include <string>
#include <vector>

#include "vri/io/oiio_input.h"
#include "vri/io/volume_formats.h"
#include "vri/util/checked_size.h"
#include "vri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// The stored type of a page's pixels; half floats are read as float32, which holds them exactly.
StoredType pageStoredType(const fs::path& path, OIIO::TypeDesc format, OIIO::TypeDesc& readAs) {
    readAs = format;
    switch (format.basetype) {
    case OIIO::TypeDesc::INT8: return StoredType::Int8;
    case OIIO::TypeDesc::UINT8: return StoredType::UInt8;
    case OIIO::TypeDesc::INT16: return StoredType::Int16;
    case OIIO::TypeDesc::UINT16: return StoredType::UInt16;
    case OIIO::TypeDesc::INT32: return StoredType::Int32;
    case OIIO::TypeDesc::UINT32: return StoredType::UInt32;
    case OIIO::TypeDesc::HALF: readAs = OIIO::TypeDesc::FLOAT; return StoredType::Float32;
    case OIIO::TypeDesc::FLOAT: return StoredType::Float32;
    case OIIO::TypeDesc::DOUBLE: return StoredType::Float64;
    default: break;
    }
    throw Error(path.string() + ": pixels of type " + std::string(format.c_str()) + " are not supported");
}

}  // namespace

Volume readTiffStack(const fs::path& path) {
    requireRegularFile(path);
    auto in = openImageInput(path);
    const OIIO::ImageSpec first = in->spec();
    if (first.nchannels != 1 || first.depth != 1)
        throw Error(path.string() + ": page 0 has " + std::to_string(first.nchannels) + " channels and depth " +
                    std::to_string(first.depth) + ", expected one channel (a grey-scale slice)");
    OIIO::TypeDesc readAs;
    const StoredType type = pageStoredType(path, first.format, readAs);
    int pages = 1;
    while (in->seek_subimage(pages, 0)) {
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.width != first.width || spec.height != first.height || spec.nchannels != 1 || spec.depth != 1 ||
            spec.format != first.format)
            throw Error(path.string() + ": page " + std::to_string(pages) + " is " + std::to_string(spec.width) + "x" +
                        std::to_string(spec.height) + " " + std::string(spec.format.c_str()) + " with " +
                        std::to_string(spec.nchannels) + " channels, expected " + std::to_string(first.width) + "x" +
                        std::to_string(first.height) + " " + std::string(first.format.c_str()) +
                        " with one, as page 0");
        ++pages;
    }
    const glm::ivec3 dims(first.width, first.height, pages);
    if (dims.x < 1 || dims.y < 1)
        throw Error(path.string() + ": pages of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + " pixels");
    const std::size_t pixelBytes = readAs.size();
    const std::size_t pageBytes = checkedBytes(path.string() + ": a page", {std::uint64_t(dims.x), std::uint64_t(dims.y), pixelBytes});
    const std::size_t bytes = checkedBytes(path.string() + ": " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                               std::to_string(dims.z) + " " + std::string(storedTypeName(type)),
                                           {pageBytes, std::uint64_t(dims.z)});
    std::string voxels(bytes, '\0');
    for (int z = 0; z < pages; ++z)
        if (!in->read_image(z, 0, 0, 1, readAs, voxels.data() + z * pageBytes))
            throw Error(path.string() + ": page " + std::to_string(z) + ": " + oneLine(in->geterror()));
    return decodeVoxels(path.string(), dims, type, nativeByteOrder(), voxels);
}

}  // namespace vri::detail
