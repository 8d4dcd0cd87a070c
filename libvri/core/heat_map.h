#pragma once
// A difference image made to be read: |a - b| as a heat map with a numbered colour bar, instead of the
// raw per-channel differences shown as RGB on black.
#include <optional>
#include <string_view>

#include "libvri/core/image.h"

namespace vri {

// How errors map to colours: linearly from 0 to `top`, or logarithmically over `decades` decades below
// `top` (top / 10^decades and less at the bottom colour, 0 included): one shared scale then shows a set
// whose errors span orders of magnitude (a coarse peer's 0.9 beside an adaptive run's 0.04), where a linear
// one leaves all but the largest maps dark.
struct HeatMapScale {
    double top = 1.0;
    bool log = false;
    int decades = 3;
};

// A heat scale's spelling (vri-diff --heat-scale, an experiment's heat_scale:): "linear" is 0 decades, "log"
// 3, "log:N" N in 1..12; nullopt for anything else.
std::optional<int> heatScaleDecades(std::string_view text);

// An RGBA image (alpha 1): the heat map of a on a white canvas, with its colour bar below. Each pixel
// of a shows e = the largest |a - b| over all channels (alpha included) through viridis (matplotlib's
// perceptually uniform map: dark blue at the bottom of the scale, green, yellow at `top`); e > top shows
// in magenta, clipped, so that a scale set below the largest error says where it is exceeded.
//
// The canvas is a.width wide, or wider when the bar's labels need it (the map then centred on it); below
// the map come 4 white rows, the 12-row colour bar from the bottom of the scale at the canvas' left edge to
// `top` at its right, 6 rows of black tick marks (linear: at 0, 1/4, 1/2, 3/4 and 1 of `top`; log: at each
// decade), 2 white rows, the ticks' values in black ("%.2g"; all, or every other one, or the two ends: as
// many as stand two characters apart), 2 white rows. The labels are heatMapLabelScale(canvas width) pixels
// per font cell (number_glyphs.h). The colours are linear values that a preview encodes to viridis' sRGB
// bytes (writePng). Throws vri::Error as requireSameShape, or when `top` is not positive and finite or
// `decades` not in 1..12.
Image heatMapImage(const Image& a, const Image& b, const HeatMapScale& scale);

// The font cell of the bar's labels in pixels: 2 on a canvas 256 pixels wide or more, else 1.
int heatMapLabelScale(int canvasWidth);

}  // namespace vri
