#pragma once
// Reading and writing images. Renders are kept as 32-bit float OpenEXR (exact, with provenance in
// the header); PNG is only a preview for figures and eyes. Every write goes through atomic_file.h
// (atomic for a file, in place for a device, FIFO or "-").
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "libvri/core/image.h"

namespace vri {

// String attributes of an image file's header, in the order given (name, value).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// Any format OpenImageIO reads (first subimage, top mip level, its data window: for our own
// files the whole image), converted to float, all channels with their names. Throws vri::Error "PATH: no such file" or "PATH: cannot read image: <why>".
Image readImage(const std::filesystem::path& path);

// The string attributes of an image file's header (ours and the ones the format adds itself).
ImageMetadata readImageMetadata(const std::filesystem::path& path);

// 32-bit float OpenEXR whatever the extension, channel names from the image. OpenEXR keeps
// channels sorted by name; OpenImageIO reads R, G, B, A back first, then the others by name.
void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata = {});

struct PngOptions {
    float exposure = 1.0f;
    bool invert = false;                       // 1 - c, for "darker = higher intensity" figures
    std::array<float, 3> background{0, 0, 0};  // seen through where alpha < 1
};

// 8-bit RGB preview, no alpha. Per pixel and colour channel, c being premultiplied:
//   v = (c + (1 - A) * background) * exposure;  v = 1 - v if invert;  clamp to [0, 1];
//   byte = floor(sRGB(v) * 255 + 0.5) (IEC 61966-2-1's encoding, rounded to nearest, halves up);
// NaN becomes 0 before inverting. The file is marked sRGB. Only the preview is encoded: the EXR
// keeps the linear values.
// The colour comes from the channels named R, G, B; without all three, the first channel that
// is not A is shown as grey. Without an A channel, A = 1 (no background shows through).
void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options = {});

// A path's extension in lower case (".exr" for "A.EXR"): how the writers below pick a format.
std::string lowercaseExtension(const std::filesystem::path& path);

// By extension: .exr -> writeExr, .png -> writePng with default options, any other format that
// OpenImageIO can encode into memory gets float data and converts it as that format can; the
// formats it cannot (SGI, FITS, ...) are an error, since their writes could not be checked.
void writeImage(const std::filesystem::path& path, const Image& image);

// The bytes each of the three writes above would put at `path` (named in their errors), for outputs
// that go out together (atomic_file.h's OutputSet): a tool whose later output fails replaces none.
std::string encodeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata = {});
std::string encodePng(const std::filesystem::path& path, const Image& image, const PngOptions& options = {});
std::string encodeImage(const std::filesystem::path& path, const Image& image);

}  // namespace vri
