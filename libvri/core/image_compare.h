#pragma once
// Per-channel error statistics between two renders of the same view (Paper B's "% of rays whose
// error exceeds 0.01 / 0.005 / 0.001" and its error histograms).
//
// Every pixel counts as a ray, background pixels that miss the volume included, so percentages
// are over width * height whatever the scene covers, unless a mask (pixel_mask.h) says which count.
//
// The error of a pixel-channel is |a - b| in double. Two NaNs, or two equal infinities, agree
// (error 0); a NaN against a number is an infinite error, so a broken render never passes.
#include <cstdint>
#include <string>
#include <vector>

#include "libvri/core/image.h"
#include "libvri/core/pixel_mask.h"

namespace vri {

struct ChannelDiff {
    std::string name;
    double maxAbs = 0;   // largest error
    double meanAbs = 0;  // mean error over all pixels
    double rmse = 0;     // root mean square error over all pixels
    int maxX = 0;        // first pixel (row-major from the top) where maxAbs occurs
    int maxY = 0;
    std::vector<double> percentAbove;        // per threshold: 100 * countAbove / pixels
    std::vector<std::uint64_t> countAbove;  // per threshold: pixels whose error > threshold (strictly)
};

struct ImageDiff {
    int width = 0;
    int height = 0;
    std::vector<double> thresholds;
    std::vector<ChannelDiff> channels;  // in the order of the images' channels, named after a's
    std::uint64_t pixels = 0;           // the pixels counted: width * height, or the mask's
    std::string mask;                   // which pixels count (PixelMask::description)
    // Per threshold: pixels whose error in some channel is above it, as OpenImageIO's idiff counts (a
    // channel's countAbove counts that channel's pixels; summed over the channels, pixel-channels).
    std::vector<std::uint64_t> pixelsAbove;
};

// One pixel-channel's error |a - b| in double, by the rules above (equal NaNs or infinities 0, a NaN against a
// number infinite): every statistic of a comparison, image_metrics.h's too, counts errors this way.
double absoluteError(float a, float b);

// Throws vri::Error naming both shapes when a and b differ in size or channel count.
void requireSameShape(const Image& a, const Image& b);

// The thresholds a comparison counts errors above when none are given (vri-diff, the Python module): the
// papers' 0.01, 0.005 and 0.001.
inline const std::vector<double> kDefaultThresholds{0.01, 0.005, 0.001};

// Deterministic (a fixed summation order in double). Over the pixels `mask` keeps (all when null); a mask
// that keeps none gives zero statistics. Throws as requireSameShape.
ImageDiff compareImages(const Image& a, const Image& b, const std::vector<double>& thresholds,
                        const PixelMask* mask = nullptr);

// Per-channel error |a - b| (as above) times `scale` (to make small errors visible in an 8-bit
// picture), channel names from a. Throws as requireSameShape.
Image differenceImage(const Image& a, const Image& b, double scale = 1.0);

// The pair as one image of three layers for an EXR viewer (tev, OpenImageIO's iv, Nuke), which lists the
// layers by their channels' prefixes: reference.<C> = a, test.<C> = b and error.<C> = |a - b| (as above),
// for each channel C of a. Throws as requireSameShape, or vri::Error when 3 x a's channels exceed the limit.
Image comparisonLayers(const Image& a, const Image& b);

// Counts of errors per bin and channel. Bins follow the "strictly above" rule of compareImages,
// so the count above any edge is the sum of the bins past it:
//   bin 0: error == 0 exactly
//   bin 1: 0 < error <= edges[0]
//   bin i (2 .. edges.size()): edges[i-2] < error <= edges[i-1]
//   last bin (edges.size() + 1): error > edges.back(), infinities included
// Every pixel-channel falls in exactly one bin: each channel's counts sum to `pixels`.
struct ErrorHistogram {
    std::vector<double> edges;  // strictly ascending, >= 0, finite
    std::vector<std::string> channelNames;
    std::vector<std::vector<std::uint64_t>> counts;  // [channel][bin], edges.size() + 2 bins
    std::uint64_t pixels = 0;

    std::size_t binCount() const { return edges.size() + 2; }
    double binLower(std::size_t bin) const;  // 0 for bins 0 and 1
    double binUpper(std::size_t bin) const;  // +infinity for the last bin
};

// Over the pixels `mask` keeps (all when null). Throws vri::Error on bad edges, and as requireSameShape.
ErrorHistogram errorHistogram(const Image& a, const Image& b, std::vector<double> edges,
                              const PixelMask* mask = nullptr);

// lo, then binsPerDecade edges per factor of ten, up to hi (lo and hi exactly; the last step may
// be shorter). Throws vri::Error unless 0 < lo < hi and binsPerDecade >= 1.
std::vector<double> logBinEdges(double lo, double hi, int binsPerDecade);

// One row per bin: bin_lo,bin_hi, then one count column per channel (R,G,B,A for renders).
// The zero bin reads 0,0; the last bin's upper bound reads inf.
std::string toCsv(const ErrorHistogram& histogram);

}  // namespace vri
