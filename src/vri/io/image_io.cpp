#include "vri/io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string_view>

#include "vri/io/oiio_input.h"
#include "vri/util/atomic_file.h"
#include "vri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// A hand-built Image can disagree with itself; writing it would read past the pixel array.
void requireConsistent(const Image& image, const fs::path& path) {
    const auto expected = static_cast<std::size_t>(std::max(image.width, 0)) * std::max(image.height, 0) *
                          std::max(image.channels, 0);
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
        image.channelNames.size() != static_cast<std::size_t>(image.channels) || image.pixels.size() != expected)
        throw Error(path.string() + ": cannot write image: inconsistent image (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ", " + std::to_string(image.channels) + " channels, " +
                    std::to_string(image.channelNames.size()) + " names, " + std::to_string(image.pixels.size()) +
                    " values)");
}

int channelIndex(const Image& image, std::string_view name) {
    auto it = std::find(image.channelNames.begin(), image.channelNames.end(), name);
    return it == image.channelNames.end() ? -1 : static_cast<int>(it - image.channelNames.begin());
}

OIIO::ImageSpec floatSpec(const Image& image) {
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    spec.channelnames = image.channelNames;
    spec.alpha_channel = channelIndex(image, "A");
    spec.z_channel = -1;
    return spec;
}

// `format` is an OpenImageIO format name ("openexr") or a file name whose extension names it. The
// image is encoded into memory, so that every byte then reaches the file through writeTextFile's
// checked writes: a file writer of OpenImageIO's can lose a failed write (a full disk gave a truncated
// EXR and success). Formats that cannot encode into memory (SGI, FITS, ...) are refused for that
// reason. has_error() is not consulted: TIFF leaves an error about its Exif directory behind even
// when the file it writes is right; the calls' results are what says whether they failed.
void writeWithOiio(const fs::path& path, const std::string& format, const OIIO::ImageSpec& spec,
                   OIIO::TypeDesc dataType, const void* data) {
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw Error(path.string() + ": cannot write image: " + detail::oneLine(OIIO::geterror()));
    if (!out->supports("ioproxy"))
        throw Error(path.string() + ": cannot write " + out->format_name() +
                    " images: OpenImageIO cannot encode them into memory to check every write (use .exr, .tif or "
                    ".png)");
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    const bool encodedAll = out->set_ioproxy(&memory) && out->open(path.string(), spec) &&
                            out->write_image(dataType, data);
    if (!out->close() || !encodedAll)
        throw Error(path.string() + ": cannot write image: " + detail::oneLine(out->geterror()));
    writeTextFile(path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1]: every viewer reads an
// 8-bit PNG as sRGB, so linear bytes would show the data darker than they are.
double srgbEncoded(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::uint8_t previewByte(float composited, const PngOptions& options) {
    float v = std::isnan(composited) ? 0.0f : composited * options.exposure;
    if (options.invert) v = 1.0f - v;
    v = std::clamp(v, 0.0f, 1.0f);
    return static_cast<std::uint8_t>(std::floor(srgbEncoded(v) * 255.0 + 0.5));
}

std::vector<std::uint8_t> previewRgb8(const Image& image, const PngOptions& options) {
    int colour[3] = {channelIndex(image, "R"), channelIndex(image, "G"), channelIndex(image, "B")};
    // A lone channel is shown as grey whatever its name, never taken for alpha.
    const int alpha = image.channels > 1 ? channelIndex(image, "A") : -1;
    if (colour[0] < 0 || colour[1] < 0 || colour[2] < 0) {
        const int grey = alpha == 0 ? 1 : 0;
        colour[0] = colour[1] = colour[2] = grey;
    }
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
    std::size_t out = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float a = alpha >= 0 ? image.at(x, y, alpha) : 1.0f;
            for (int k = 0; k < 3; ++k)
                rgb[out++] = previewByte(image.at(x, y, colour[k]) + (1.0f - a) * options.background[k], options);
        }
    return rgb;
}

std::string lowercaseExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
    return ext;
}

}  // namespace

Image readImage(const fs::path& path) {
    auto in = detail::openImageInput(path);
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.depth > 1)
        throw Error(path.string() + ": cannot read image: it is a volume image (depth " + std::to_string(spec.depth) +
                    "), not a 2D image");
    try {
        imageBytes(spec.width, spec.height, spec.nchannels);  // the header's size, checked before allocating
    } catch (const Error& e) {
        throw Error(path.string() + ": " + e.what());
    }
    Image image(spec.width, spec.height, spec.nchannels);
    for (int c = 0; c < spec.nchannels; ++c)
        if (c < static_cast<int>(spec.channelnames.size()) && !spec.channelnames[c].empty())
            image.channelNames[c] = spec.channelnames[c];
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw Error(path.string() + ": cannot read image: " + detail::oneLine(in->geterror()));
    in->close();
    return image;
}

ImageMetadata readImageMetadata(const fs::path& path) {
    auto in = detail::openImageInput(path);
    ImageMetadata metadata;
    for (const OIIO::ParamValue& attribute : in->spec().extra_attribs)
        if (attribute.type() == OIIO::TypeDesc::STRING)
            metadata.emplace_back(attribute.name().string(), attribute.get_string());
    return metadata;
}

void writeExr(const fs::path& path, const Image& image, const ImageMetadata& metadata) {
    requireConsistent(image, path);
    OIIO::ImageSpec spec = floatSpec(image);
    for (const auto& [name, value] : metadata) spec.attribute(name, value);
    writeWithOiio(path, "openexr", spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

void writePng(const fs::path& path, const Image& image, const PngOptions& options) {
    requireConsistent(image, path);
    const std::vector<std::uint8_t> rgb = previewRgb8(image, options);
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");  // the PNG says so (its sRGB chunk)
    writeWithOiio(path, "png", spec, OIIO::TypeDesc::UINT8, rgb.data());
}

void writeImage(const fs::path& path, const Image& image) {
    const std::string ext = lowercaseExtension(path);
    if (ext == ".exr") return writeExr(path, image);
    if (ext == ".png") return writePng(path, image);
    requireConsistent(image, path);
    writeWithOiio(path, path.string(), floatSpec(image), OIIO::TypeDesc::FLOAT, image.pixels.data());
}

}  // namespace vri
