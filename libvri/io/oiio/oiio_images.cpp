// 2D images of any format OpenImageIO reads or can encode into memory.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>


#include "libvri/io/oiio/oiio_functions.h"
#include "libvri/util/error.h"
#include "libvri/util/printable.h"

namespace vri::detail::oiio {

namespace fs = std::filesystem;

namespace {

std::unique_ptr<OIIO::ImageInput> openInput(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image: " + oneLine(OIIO::geterror()));
    return in;
}

}  // namespace

std::string readImage(const fs::path& path, Image& image) {
    return caughtMessage("OpenImageIO", [&] {
        auto in = openInput(path);
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.depth > 1)
            throw Error(path.string() + ": cannot read image: it is a volume image (depth " +
                        std::to_string(spec.depth) + "), not a 2D image");
        try {
            image = Image(spec.width, spec.height, spec.nchannels);  // the header's size, checked before allocating
        } catch (const Error& e) {
            throw Error(path.string() + ": " + e.what());
        }
        for (int c = 0; c < spec.nchannels; ++c)
            if (c < static_cast<int>(spec.channelnames.size()) && !spec.channelnames[c].empty())
                image.channelNames[c] = spec.channelnames[c];
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
            throw Error(path.string() + ": cannot read image: " + oneLine(in->geterror()));
        in->close();
    });
}

std::string readImageMetadata(const fs::path& path, ImageMetadata& metadata) {
    return caughtMessage("OpenImageIO", [&] {
        auto in = openInput(path);
        for (const OIIO::ParamValue& attribute : in->spec().extra_attribs)
            if (attribute.type() == OIIO::TypeDesc::STRING)
                metadata.emplace_back(attribute.name().string(), attribute.get_string());
    });
}

// The format is the one the path's extension names. The image is encoded into memory, so that every byte
// then reaches the file through the caller's checked writes: a file writer of OpenImageIO's can lose a failed
// write (a full disk gave a truncated EXR and success). Formats that cannot encode into memory (SGI, FITS,
// ...) are refused for that reason. has_error() is not consulted: TIFF leaves an error about its Exif
// directory behind even when the file it writes is right; the calls' results say whether they failed.
std::string encodeImage(const fs::path& path, const Image& image, std::string& bytes) {
    return caughtMessage("OpenImageIO", [&] {
        auto out = OIIO::ImageOutput::create(path.string());
        if (!out) throw Error(path.string() + ": cannot write image: " + oneLine(OIIO::geterror()));
        if (!out->supports("ioproxy"))
            throw Error(path.string() + ": cannot write " + out->format_name() +
                        " images: OpenImageIO cannot encode them into memory to check every write (use .exr, .tif "
                        "or .png)");
        OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
        spec.channelnames = image.channelNames;
        spec.alpha_channel = channelIndex(image, "A");
        spec.z_channel = -1;
        std::vector<unsigned char> encoded;
        OIIO::Filesystem::IOVecOutput memory(encoded);
        const bool encodedAll = out->set_ioproxy(&memory) && out->open(path.string(), spec) &&
                                out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
        if (!out->close() || !encodedAll)
            throw Error(path.string() + ": cannot write image: " + oneLine(out->geterror()));
        bytes.assign(reinterpret_cast<const char*>(encoded.data()), encoded.size());
    });
}

}  // namespace vri::detail::oiio
