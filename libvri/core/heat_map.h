#pragma once
// A difference image made to be read: |a - b| as a heat map with a numbered colour bar, instead of the
// raw per-channel differences shown as RGB on black.
#include "libvri/core/image.h"

namespace vri {

// An RGBA image (alpha 1): the heat map of a on a white canvas, with its colour bar below. Each pixel
// of a shows e = the largest |a - b| over all channels (alpha included) through viridis (matplotlib's
// perceptually uniform map: dark blue at 0, green, yellow at `top`; e >= top shows as yellow).
//
// The canvas is a.width wide, or wider when the bar's labels need it (the map then centred on it); below
// the map come 4 white rows, the 12-row colour bar from 0 at the canvas' left edge to `top` at its right,
// 6 rows of black tick marks at 0, 1/4, 1/2, 3/4 and 1 of `top`, 2 white rows, the ticks' values in black
// ("%.2g"; all five, or those at 0, 1/2 and 1, or at 0 and 1: as many as stand two characters apart), 2 white rows. The
// labels are heatMapLabelScale(canvas width) pixels per font cell (number_glyphs.h). The colours are
// linear values that a preview encodes to viridis' sRGB bytes (writePng). Throws vri::Error as
// requireSameShape, or when `top` is not positive and finite.
Image heatMapImage(const Image& a, const Image& b, double top);

// The font cell of the bar's labels in pixels: 2 on a canvas 256 pixels wide or more, else 1.
int heatMapLabelScale(int canvasWidth);

}  // namespace vri
