#include "libvri/io/viewer_floats.h"

#include <bit>
#include <cstring>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "libvri/util/base64.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/script_json.h"

namespace vri {

namespace {

std::string zlibCompressed(const std::string& bytes, const std::string& what) {
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string packed(checkedBytes(what, {size}), '\0');
    if (compress2(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                  static_cast<uLong>(bytes.size()), 6) != Z_OK)
        throw Error(what + ": zlib could not compress the pixels");
    packed.resize(size);
    return packed;
}

}  // namespace

std::string viewerFloatsScript(const std::string& id, const Image& image) {
    static_assert(std::endian::native == std::endian::little, "the viewer's floats are little-endian");
    const std::string what = "viewer floats of " + id;
    std::string bytes(checkedBytes(what, {image.pixels.size(), sizeof(float)}), '\0');
    std::memcpy(bytes.data(), image.pixels.data(), bytes.size());
    const nlohmann::json record{{"id", id},
                                {"width", image.width},
                                {"height", image.height},
                                {"channels", image.channelNames},
                                {"encoding", "f32le-zlib-base64"},
                                {"data", base64Encode(zlibCompressed(bytes, what))}};
    return "vriViewerFloats(" + scriptSafeJson(record) + ");\n";
}

}  // namespace vri
