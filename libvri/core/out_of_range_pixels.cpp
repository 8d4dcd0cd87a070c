#include "libvri/core/out_of_range_pixels.h"

#include <limits>
#include <vector>

namespace vri {

OutOfRangePixels findOutOfRangePixels(const Image& image) {
    OutOfRangePixels found;
    found.max = -std::numeric_limits<float>::infinity();
    found.min = std::numeric_limits<float>::infinity();
    const std::size_t channels = static_cast<std::size_t>(image.channels);
    std::vector<std::size_t> colour;  // R, G, B and A, in the image's order: a brick layer's brick_order is none
    for (const char* name : {"R", "G", "B", "A"})
        if (const int c = channelIndex(image, name); c >= 0) colour.push_back(static_cast<std::size_t>(c));
    for (std::size_t p = 0; p + channels <= image.pixels.size(); p += channels) {
        bool outside = false;
        for (const std::size_t c : colour) {
            const float v = image.pixels[p + c];
            if (v > found.max) found.max = v;  // false for NaN
            if (v < found.min) found.min = v;
            if (v > 1.0f) ++found.channelsAbove;
            if (v < 0.0f) ++found.channelsBelow;
            outside = outside || v > 1.0f || v < 0.0f;
        }
        if (outside) ++found.pixels;
    }
    return found;
}

void clampToUnitRange(Image& image) {
    for (float& v : image.pixels) v = v > 1.0f ? 1.0f : v < 0.0f ? 0.0f : v;
}

}  // namespace vri
