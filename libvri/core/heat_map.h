#pragma once
// A difference image made to be read: |a - b| as a heat map with its colour bar, instead of the raw
// per-channel differences shown as RGB on black.
#include "libvri/core/image.h"

namespace vri {

// The heat map's height beyond the image: a white gap, the colour bar, and its tick marks.
inline constexpr int kHeatMapBarRows = 24;

// An RGBA image (alpha 1) of width a.width and height a.height + kHeatMapBarRows. Each pixel of the
// top part shows e = the largest |a - b| over all channels (alpha included) through viridis
// (matplotlib's perceptually uniform map: dark blue at 0, green, yellow at `top`; e >= top shows as
// yellow). Below it, after a 4-row white gap, a 12-row colour bar runs from 0 at the left edge to
// `top` at the right, with black ticks (6 rows) at 0, 1/4, 1/2, 3/4 and 1 of `top`. The colours are
// linear values that a preview encodes to viridis' sRGB bytes (writePng). Throws vri::Error as
// requireSameShape, or when `top` is not positive and finite.
Image heatMapImage(const Image& a, const Image& b, double top);

}  // namespace vri
