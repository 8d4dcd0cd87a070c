// TIFF stacks' pages (the layout and its checks are tiff_stack_io.cpp's): a multi-page TIFF whose pages
// (subimages) are the z slices, each one channel of the same width, height and type.
#include <algorithm>
#include <cstring>
#include <vector>

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

std::string readTiffStack(const fs::path& path, const TiffStackRead& read) {
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
        const VoxelBox box = read.box.value_or(VoxelBox{{0, 0, 0}, {shape.width, shape.height, shape.pages}});
        for (int a = 0; a < 3; ++a)
            if (box.lo[a] < 0 || box.lo[a] >= box.hi[a] ||
                box.hi[a] > glm::ivec3(shape.width, shape.height, shape.pages)[a])
                throw Error(path.string() + ": the box of voxels does not lie inside the stack's " +
                            std::to_string(shape.width) + "x" + std::to_string(shape.height) + "x" +
                            std::to_string(shape.pages));
        char* voxels = read.allocate(shape);  // checks the sizes against the limits before allocating
        if (!voxels) return;
        const std::size_t size = readAs.size(), pageRowBytes = std::size_t(shape.width) * size;
        const std::size_t rowBytes = std::size_t(box.hi.x - box.lo.x) * size;
        const std::size_t slabBytes = rowBytes * std::size_t(box.hi.y - box.lo.y);
        // Rows are read whole, a run of them at a time, and the box's columns kept: OpenImageIO reads no part
        // of a row. A box as wide as the page is read straight into the buffer.
        const bool wholeRows = box.lo.x == 0 && box.hi.x == shape.width;
        constexpr std::size_t kRunBytes = std::size_t(1) << 20;
        const int runRows = wholeRows ? box.hi.y - box.lo.y
                                      : static_cast<int>(std::clamp<std::size_t>(kRunBytes / pageRowBytes, 1,
                                                                                 std::size_t(box.hi.y - box.lo.y)));
        std::vector<char> run(wholeRows ? 0 : std::size_t(runRows) * pageRowBytes);
        // read_scanlines succeeds on a page whose strips or tiles end early (libtiff reports a short read, the
        // rest of the page stays as it was): the error that it leaves behind marks the page as bad. libtiff's
        // warnings about a page's directory (an unknown tag) are errors to OpenImageIO too: they are dropped
        // once the seek to the page has read it, so that only what the read itself reports counts.
        for (int z = box.lo.z; z < box.hi.z; ++z) {
            const auto pageError = [&] {
                return Error(path.string() + ": page " + std::to_string(z) + ": " + oneLine(in->geterror()));
            };
            if (!in->seek_subimage(z, 0)) throw pageError();
            (void)in->geterror();
            char* page = voxels + (read.pageRead ? 0 : std::size_t(z - box.lo.z) * slabBytes);
            for (int y = box.lo.y; y < box.hi.y; y += runRows) {
                const int end = std::min(y + runRows, box.hi.y);
                char* rows = page + std::size_t(y - box.lo.y) * rowBytes;
                if (!in->read_scanlines(z, 0, y, end, 0, 0, 1, readAs, wholeRows ? rows : run.data()) ||
                    in->has_error())
                    throw pageError();
                if (wholeRows) continue;
                for (int r = 0; r < end - y; ++r)
                    std::memcpy(rows + std::size_t(r) * rowBytes,
                                run.data() + std::size_t(r) * pageRowBytes + std::size_t(box.lo.x) * size, rowBytes);
            }
            if (read.pageRead) read.pageRead(z);
        }
    });
}

}  // namespace vri::detail::oiio
