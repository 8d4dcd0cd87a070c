#include "libvri/core/pixel_mask.h"

#include <cmath>

#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/parse.h"
#include "libvri/util/printable.h"

namespace vri {

PixelMask fullMask(int width, int height) {
    PixelMask mask;
    mask.keep.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 1);
    mask.count = mask.keep.size();
    mask.description = kAllPixels;
    return mask;
}

PixelMask alphaMask(const Image& a, const Image& b, double level) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw Error("an alpha mask needs two images of one shape");
    if (a.channels < 4) throw Error("an alpha mask needs images with alpha (4 channels), got " + std::to_string(a.channels));
    PixelMask mask;
    mask.keep.resize(static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height));
    const std::size_t alpha = static_cast<std::size_t>(a.channels) - 1;
    for (std::size_t p = 0; p < mask.keep.size(); ++p) {
        const std::size_t i = p * static_cast<std::size_t>(a.channels) + alpha;
        mask.keep[p] = a.pixels[i] > level || b.pixels[i] > level;
        mask.count += mask.keep[p];
    }
    mask.description = level == 0.0 ? "the pixels the volume covers in either image, alpha > 0"
                                     : "the pixels with alpha > " + exactNumber(level) + " in either image";
    return mask;
}

PixelMask imageMask(const Image& image, int width, int height) {
    if (image.width != width || image.height != height)
        throw Error("the mask image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    ", the images " + std::to_string(width) + "x" + std::to_string(height));
    PixelMask mask;
    mask.keep.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (std::size_t p = 0; p < mask.keep.size(); ++p) {
        mask.keep[p] = image.pixels[p * static_cast<std::size_t>(image.channels)] != 0.0f;
        mask.count += mask.keep[p];
    }
    mask.description = "the mask image's non-zero pixels";
    return mask;
}

MaskSpec parseMaskSpec(const std::string& text) {
    MaskSpec spec;
    if (text == "all") return spec;
    if (text == "hit") {
        spec.kind = MaskSpec::Kind::Alpha;
        return spec;
    }
    if (text.starts_with("alpha>")) {
        const std::optional<double> level = numberFromText(text.substr(6));
        if (!level || !(*level >= 0.0 && *level < 1.0))
            throw Error("'" + printable(text) + "': expected alpha>T with T a number in [0, 1)");
        spec.kind = MaskSpec::Kind::Alpha;
        spec.level = *level;
        return spec;
    }
    if (text.empty()) throw Error("expected all, hit, alpha>T or a mask image's path, got nothing");
    spec.kind = MaskSpec::Kind::Image;
    spec.file = text;
    return spec;
}

}  // namespace vri
