#pragma once
// FLIP, the perceptual image difference of Andersson et al.: per pixel, how different the test image looks
// from the reference to an observer flipping between the two, in [0, 1].
//  - LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A Difference
//    Evaluator for Alternating Images", HPG 2020): a colour pipeline (both images filtered by the contrast
//    sensitivity functions of the opponent channels, compared in Hunt-adjusted L*a*b* with the HyAB
//    distance, the distance compressed into [0, 1]) and a feature pipeline (edges and points the observer
//    can resolve, found with Gaussian derivatives, in one image and not the other). The error is
//    colour^(1 - feature): a difference in features raises a colour error towards 1.
//  - HDR-FLIP (Andersson, Nilsson, Shirley and Akenine-Moller, "Visualizing Errors in Rendered High Dynamic
//    Range Images", Eurographics 2021 short papers): LDR-FLIP of the two images exposed and tone mapped
//    over a range of exposures, the largest error per pixel.
// The constants, filters and pipeline follow the papers and the authors' reference implementation
// (github.com/NVlabs/flip, v1.6), whose results these reproduce (tests/unit/flip_test.cpp); the arithmetic
// is in float, as theirs.
//
// Inputs are linear RGB, as vri renders are (premultiplied, so already composited over black): the
// channels named R, G and B, found by name; any others (A) are ignored. LDR-FLIP is defined on images a
// display shows, in [0, 1]: it takes the linear values clamped to [0, 1] (the papers' pipeline starts from
// sRGB-encoded pixels and decodes them to exactly these linear values). HDR-FLIP takes any finite values.
// A NaN or infinity in R, G or B is an error: a broken render has no perceived difference.
#include <cstdint>
#include <optional>
#include <vector>

#include "libvri/core/image.h"
#include "libvri/core/pixel_mask.h"

namespace vri {

// How the images are seen: from `monitorDistance` metres, on a monitor `monitorWidth` metres wide showing
// `monitorPixelsWide` pixels across. The defaults are the papers': a 0.7 m wide 4K monitor at 0.7 m.
struct FlipViewing {
    double monitorDistance = 0.7;
    double monitorWidth = 0.7;
    double monitorPixelsWide = 3840;
    // Pixels per degree of visual angle, distance * (pixels / width) * pi / 180 (the small-angle
    // approximation, as the papers): about 67.02 for the defaults. Every filter's width is set by it.
    double pixelsPerDegree() const;
};

// The tone curves HDR-FLIP can expose through: ACES (Narkowicz's fit, the papers' default), Hable's filmic
// curve (a rational fit of it) and Reinhard's x / (1 + luminance).
enum class FlipToneMapper { Aces, Hable, Reinhard };

// HDR-FLIP's exposures, as log2 multipliers of the linear values: `count` of them, evenly spaced from
// `start` to `stop` inclusive.
struct FlipExposureRange {
    double start = 0;
    double stop = 0;
    int count = 0;
};

struct FlipHdrOptions {
    FlipToneMapper toneMapper = FlipToneMapper::Aces;
    // A start or stop not given is flipExposureRange's over all of the reference's pixels, as the papers';
    // a count not given is max(2, ceil(stop - start)) of the start and stop used.
    std::optional<double> startExposure;
    std::optional<double> stopExposure;
    std::optional<int> exposures;  // at least 2
};

struct FlipResult {
    std::vector<float> errorMap;  // width * height errors in [0, 1], row 0 at the top; every pixel
    int width = 0;
    int height = 0;
    // Over the pixels the mask keeps (all without one); all 0 when it keeps none.
    std::uint64_t pixels = 0;
    double mean = 0;
    double median = 0;  // percentiles interpolate linearly between the sorted errors at q * (pixels - 1)
    double p95 = 0;
    double max = 0;
    // HDR-FLIP's range of exposures; count 0 for LDR-FLIP.
    FlipExposureRange exposures;
};

// LDR-FLIP of `test` against `reference`. Throws vri::Error when the images differ in size, lack an R, G or
// B channel or hold a non-finite value there, or when the mask is not theirs.
FlipResult ldrFlip(const Image& reference, const Image& test, const FlipViewing& viewing = {},
                   const PixelMask* mask = nullptr);

// HDR-FLIP of `test` against `reference`: throws as ldrFlip, and when the exposures are out of order,
// outside [-126, 126] (beyond float's range) or fewer than 2, or those to compute cannot be (below).
FlipResult hdrFlip(const Image& reference, const Image& test, const FlipViewing& viewing = {},
                   const PixelMask* mask = nullptr, const FlipHdrOptions& options = {});

// The HDR-FLIP paper's exposure range for a reference image and tone curve: start exposes the brightest
// luminance, stop the median one, to the input at which the curve reaches 0.85 (so the range runs from the
// highlights barely clipping to the typical pixel well exposed), and count = max(2, ceil(stop - start)),
// one exposure per stop. Over the pixels `mask` keeps (all without one): a render over a black background
// whose median pixel is black would otherwise have no stop exposure. The median is the luminance of rank
// n / 2 counted from 0 (the upper one of an even count), as the reference implementation picks. Throws
// vri::Error as ldrFlip, and when the brightest or median luminance is not positive.
FlipExposureRange flipExposureRange(const Image& reference, FlipToneMapper toneMapper = FlipToneMapper::Aces,
                                    const PixelMask* mask = nullptr);

}  // namespace vri
