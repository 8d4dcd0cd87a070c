#pragma once
// Pixels with a channel outside [0, 1]. The exact integral keeps alpha in [0, 1], and the colour too when
// emission is colour times extinction and the colours are; a quadrature need not. Paper B's alpha is the
// integral of extinction times transparency, which Simpson's rule over a steep rise (or a step across a
// transfer-function jump) carries past 1, and its colours with it; a Riemann sum's tau * h * T overshoots
// where tau * h is large. They are counted after every render, as non-finite pixels are, not predicted.
#include <cstdint>

#include "libvri/core/image.h"

namespace vri {

struct OutOfRangePixels {
    std::uint64_t pixels = 0;         // pixels with at least one channel above 1 or below 0
    std::uint64_t channelsAbove = 0;  // channel values above 1
    std::uint64_t channelsBelow = 0;  // channel values below 0
    // The largest and the smallest channel value of the image (NaN left out; -inf and +inf when
    // every value is NaN).
    float max = 0.0f, min = 0.0f;
};

// Counts the channels named R, G, B and A (a render's colour and alpha), not others such as a brick layer's
// brick_order.
OutOfRangePixels findOutOfRangePixels(const Image& image);
// Clamps every channel to [0, 1] (--clamp); NaN stays NaN.
void clampToUnitRange(Image& image);

}  // namespace vri
