#pragma once
// A difference image made to be read: |a - b| as a heat map with a numbered colour bar, instead of the
// raw per-channel differences shown as RGB on black.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/core/image.h"
#include "libvri/core/pixel_mask.h"

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

// The rule for a scale's top when none is given (vri-diff --heat-top, an experiment's heat_top:): "max", the
// largest error of the set (100), or "pN", its Nth percentile (N in (0, 100]), which a single outlier (one
// Riemann overshoot of 3.28 among errors of 0.01) cannot set: the maps then show every run's structure
// and mark the few pixels above in magenta. nullopt for anything else.
std::optional<double> heatTopPercentile(std::string_view text);

// The top for a set of comparisons against `a`: the `percentile` (nearest rank) of the largest |a - x| over
// the channels of each pixel, pooled over every x in `set`, counting only the pixels `mask` keeps (all
// without one) whose error is not 0 (the background both leave empty would otherwise set every percentile
// to 0). 0 when no pixel differs; infinite when the rank falls on a NaN against a number. Throws
// vri::Error as requireSameShape.
double heatMapTop(const Image& a, const std::vector<const Image*>& set, double percentile,
                  const PixelMask* mask = nullptr);

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
// per font cell (text_glyphs.h). The colours are linear values that a preview encodes to viridis' sRGB
// bytes (writePng). A non-empty `title` (what is compared, the value and the scale) is drawn in black in
// a line above the map (2 white rows, the glyphs a cell in from the left, 4 white rows), cut with ".." where
// the canvas is too narrow.
// Throws vri::Error as requireSameShape, or when `top` is not positive and finite or `decades` not in 1..12.
Image heatMapImage(const Image& a, const Image& b, const HeatMapScale& scale, const std::string& title = "");

// The signed differences b - a, one map per channel side by side (named under each, 8 white columns between
// them), on a diverging scale from -top (blue) through 0 (light grey) to +top (red), larger magnitudes (and
// NaN) in black, with a bar numbered at -top, 0 and +top; linear only. A run that is brighter than the reference
// in red and darker in alpha shows as such, where the unsigned map shows only that they differ.
Image signedHeatMapImage(const Image& a, const Image& b, double top, const std::string& title = "");

// The font cell of the bar's labels in pixels: 2 on a canvas 256 pixels wide or more, else 1.
int heatMapLabelScale(int canvasWidth);

}  // namespace vri
