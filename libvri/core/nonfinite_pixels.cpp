#include "libvri/core/nonfinite_pixels.h"

#include <cmath>

#include "libvri/util/format.h"

namespace vri {

NonFinitePixels findNonFinitePixels(const Image& image) {
    NonFinitePixels found;
    const std::size_t n = static_cast<std::size_t>(image.channels);
    found.pixels = image.pixels.size() / n;
    for (std::size_t p = 0; p < found.pixels; ++p) {
        const float* v = &image.pixels[p * n];
        bool finite = true;
        for (std::size_t c = 0; c < n; ++c) finite = finite && std::isfinite(v[c]);
        if (finite) continue;
        if (found.count++ == 0) {
            found.firstX = static_cast<int>(p % static_cast<std::size_t>(image.width));
            found.firstY = static_cast<int>(p / static_cast<std::size_t>(image.width));
            for (std::size_t c = 0; c < n; ++c)
                found.firstValues += (c ? " " : "") + image.channelNames[c] + "=" + exactNumber(v[c]);
        }
    }
    return found;
}

std::string NonFinitePixels::describe() const {
    const std::string text = std::to_string(count) + " of " + std::to_string(pixels) + " pixels are not finite";
    if (count == 0) return text;
    return text + " (first at " + std::to_string(firstX) + "," + std::to_string(firstY) + ": " + firstValues + ")";
}

}  // namespace vri
