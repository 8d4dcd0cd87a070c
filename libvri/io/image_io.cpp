#include "libvri/io/image_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string_view>

#include "libvri/io/exr_file.h"
#include "libvri/io/io_module.h"
#include "libvri/io/oiio_module.h"
#include "libvri/io/png_file.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/printable.h"

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

// Encodes the image in memory; a library's failure becomes "PATH: cannot write image: <why>".
template <typename Encode>
std::string encoded(const fs::path& path, const Image& image, Encode&& encode) {
    requireConsistent(image, path);
    try {
        return encode();
    } catch (const std::exception& e) {
        throw Error(path.string() + ": cannot write image: " + oneLine(e.what()));
    }
}

}  // namespace

std::string lowercaseExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
    return ext;
}

// An OpenEXR file goes to OpenEXR whatever its extension; everything else to OpenImageIO's module.
Image readImage(const fs::path& path) {
    if (!fs::exists(path)) throw Error(path.string() + ": no such file");
    if (detail::isExrFile(path)) return detail::readExrFile(path);
    Image image;
    detail::requireModuleSuccess(detail::oiioModule(path, "read image").readImage(path, image));
    return image;
}

ImageMetadata readImageMetadata(const fs::path& path) {
    if (!fs::exists(path)) throw Error(path.string() + ": no such file");
    if (detail::isExrFile(path)) return detail::readExrMetadata(path);
    ImageMetadata metadata;
    detail::requireModuleSuccess(detail::oiioModule(path, "read image").readImageMetadata(path, metadata));
    return metadata;
}

std::string encodeExr(const fs::path& path, const Image& image, const ImageMetadata& metadata) {
    return encoded(path, image, [&] { return detail::encodeExr(image, metadata); });
}

std::string encodePng(const fs::path& path, const Image& image, const PngOptions& options) {
    return encoded(path, image,
                   [&] { return detail::encodePngRgb8(image.width, image.height, previewRgb8(image, options)); });
}

std::string encodeImage(const fs::path& path, const Image& image) {
    const std::string ext = lowercaseExtension(path);
    if (ext == ".exr") return encodeExr(path, image);
    if (ext == ".png") return encodePng(path, image);
    requireConsistent(image, path);
    std::string bytes;
    detail::requireModuleSuccess(detail::oiioModule(path, "write image").encodeImage(path, image, bytes));
    return bytes;
}

void writeExr(const fs::path& path, const Image& image, const ImageMetadata& metadata) {
    writeTextFile(path, encodeExr(path, image, metadata));
}

void writePng(const fs::path& path, const Image& image, const PngOptions& options) {
    writeTextFile(path, encodePng(path, image, options));
}

void writeImage(const fs::path& path, const Image& image) { writeTextFile(path, encodeImage(path, image)); }

}  // namespace vri
