// TIFF stacks' pages (the layout and its checks are tiff_stack_io.cpp's): a multi-page TIFF whose pages
// (subimages) are the z slices, each one channel of the same width, height and type.
#include <OpenImageIO/imageio.h>

#include "libvri/io/oiio/oiio_functions.h"
#include "libvri/util/error.h"
#include "libvri/util/printable.h"

namespace vri::detail::oiio {

namespace fs = std::filesystem;

namespace {

// The stored type of a page's pixels, and the type to read them as (half floats as float32).
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

std::string readTiffStack(const fs::path& path, const std::function<char*(const TiffStackShape&)>& allocate) {
    return caughtMessage("OpenImageIO", [&] {
        auto in = OIIO::ImageInput::open(path.string());
        if (!in) throw Error(path.string() + ": cannot read image: " + oneLine(OIIO::geterror()));
        const OIIO::ImageSpec first = in->spec();
        if (first.nchannels != 1 || first.depth != 1)
            throw Error(path.string() + ": page 0 has " + std::to_string(first.nchannels) + " channels and depth " +
                        std::to_string(first.depth) + ", expected one channel (a grey-scale slice)");
        TiffStackShape shape{first.width, first.height, 1, StoredType::UInt8};
        OIIO::TypeDesc readAs;
        shape.type = pageStoredType(path, first.format, readAs);
        while (in->seek_subimage(shape.pages, 0)) {
            const OIIO::ImageSpec& spec = in->spec();
            if (spec.width != first.width || spec.height != first.height || spec.nchannels != 1 || spec.depth != 1 ||
                spec.format != first.format)
                throw Error(path.string() + ": page " + std::to_string(shape.pages) + " is " +
                            std::to_string(spec.width) + "x" + std::to_string(spec.height) + " " +
                            std::string(spec.format.c_str()) + " with " + std::to_string(spec.nchannels) +
                            " channels, expected " + std::to_string(first.width) + "x" + std::to_string(first.height) +
                            " " + std::string(first.format.c_str()) + " with one, as page 0");
            ++shape.pages;
        }
        char* voxels = allocate(shape);  // checks the pages' size against the limits before allocating
        const std::size_t pageBytes = std::size_t(shape.width) * std::size_t(shape.height) * readAs.size();
        // read_image succeeds on a page whose strips or tiles end early (libtiff reports a short read, the
        // rest of the page stays as it was): the error that it leaves behind marks the page as bad. libtiff's
        // warnings about a page's directory (an unknown tag) are errors to OpenImageIO too: they are dropped
        // once the seek to the page has read it, so that only what the read itself reports counts.
        for (int z = 0; z < shape.pages; ++z) {
            if (!in->seek_subimage(z, 0))
                throw Error(path.string() + ": page " + std::to_string(z) + ": " + oneLine(in->geterror()));
            (void)in->geterror();
            if (!in->read_image(z, 0, 0, 1, readAs, voxels + std::size_t(z) * pageBytes) || in->has_error())
                throw Error(path.string() + ": page " + std::to_string(z) + ": " + oneLine(in->geterror()));
        }
    });
}

}  // namespace vri::detail::oiio
