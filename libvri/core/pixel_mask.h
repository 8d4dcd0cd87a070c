#pragma once
// Which pixels an error statistic counts. By default every pixel counts as a ray, the background
// included (paper B's percentages), so a statistic changes with the framing: a plume filling a fifth of the
// frame dilutes every number fivefold. A mask restricts every statistic of a comparison to the pixels
// that matter: those the volume covers in either image (hit: alpha > 0), those above an alpha level, or
// the non-zero pixels of a mask image.
#include <cstdint>
#include <string>
#include <vector>

#include "libvri/core/image.h"

namespace vri {

struct PixelMask {
    std::vector<std::uint8_t> keep;  // width * height, rows from the top: 1 where the pixel counts
    std::uint64_t count = 0;         // pixels kept
    std::string description;         // "all pixels", "alpha > 0 in either image", ...
    bool all() const { return count == keep.size(); }
};

// What a statistic over every pixel says it counts.
inline constexpr const char* kAllPixels = "all pixels, background included";

// Every pixel of a width x height image.
PixelMask fullMask(int width, int height);

// The pixels where the alpha channel (the last) of `a` or of `b` is above `level`: level 0 keeps the rays
// that hit something of the volume in either image. Throws vri::Error when the images differ in shape or
// have no alpha (fewer than 4 channels).
PixelMask alphaMask(const Image& a, const Image& b, double level);

// The pixels where the mask image's first channel is not 0; throws vri::Error naming both sizes when it is not
// width x height.
PixelMask imageMask(const Image& mask, int width, int height);

// A mask from its command-line spelling: "all", "hit" (alpha > 0 in either image), "alpha>T" (T a number in
// [0, 1)), or the path of a mask image, read by `readMask`. Throws vri::Error naming what was expected.
struct MaskSpec {
    enum class Kind { All, Alpha, Image } kind = Kind::All;
    double level = 0.0;  // Alpha
    std::string file;    // Image
};
MaskSpec parseMaskSpec(const std::string& text);

}  // namespace vri
