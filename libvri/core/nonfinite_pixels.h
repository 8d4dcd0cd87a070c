#pragma once
// Pixels holding NaN or an infinity. A render leaves them where its arithmetic overflowed: an extinction
// so large that the Riemann sum's tau * dx * C passes float's range, or that Simpson's quadratic through
// a jump extrapolates a negative optical depth whose exponential overflows (Inf * 0 then gives NaN).
// They are found after the render, one pass over the image, rather than predicted: whether a ray meets
// such a value depends on the step, the path and the transfer-function segment it samples.
#include <cstdint>
#include <string>

#include "libvri/core/image.h"

namespace vri {

struct NonFinitePixels {
    std::uint64_t count = 0;       // pixels with at least one non-finite channel
    std::uint64_t pixels = 0;      // pixels looked at
    int firstX = -1, firstY = -1;  // the first of them in row order (top row first); -1 when none
    std::string firstValues;       // its channels, "R=inf G=nan B=inf A=1"

    // "3 of 256 pixels are not finite (first at 4,2: R=inf G=nan B=inf A=1)"
    std::string describe() const;
};

NonFinitePixels findNonFinitePixels(const Image& image);

}  // namespace vri
