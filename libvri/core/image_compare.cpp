#include "libvri/core/image_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Calls f(channel, x, y, error) for every pixel-channel the mask keeps (all when null), rows from the top,
// channels innermost. a and b have the same shape, the mask theirs.
template <class F>
void forEachError(const Image& a, const Image& b, const PixelMask* mask, F&& f) {
    std::size_t i = 0, p = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x, ++p) {
            if (mask && !mask->keep[p]) {
                i += static_cast<std::size_t>(a.channels);
                continue;
            }
            for (int c = 0; c < a.channels; ++c, ++i) f(c, x, y, absoluteError(a.pixels[i], b.pixels[i]));
        }
}

void requireMaskOf(const Image& a, const PixelMask* mask) {
    if (mask && mask->keep.size() != static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height))
        throw Error("the mask has " + std::to_string(mask->keep.size()) + " pixels, the images " +
                    std::to_string(static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height)));
}

std::string shape(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
           std::to_string(image.channels) + " channels";
}

void requireValidEdges(const std::vector<double>& edges) {
    if (edges.empty()) throw Error("histogram needs at least one bin edge");
    for (std::size_t i = 0; i < edges.size(); ++i) {
        if (!std::isfinite(edges[i]) || edges[i] < 0)
            throw Error("histogram bin edges must be finite and >= 0, got " + exactNumber(edges[i]));
        if (i > 0 && !(edges[i] > edges[i - 1]))
            throw Error("histogram bin edges must be strictly ascending, got " + exactNumber(edges[i - 1]) +
                        " then " + exactNumber(edges[i]));
    }
}

}  // namespace

double absoluteError(float a, float b) {
    if (a == b) return 0.0;  // also equal infinities, whose difference would be NaN
    if (std::isnan(a) && std::isnan(b)) return 0.0;
    const double d = std::abs(static_cast<double>(a) - static_cast<double>(b));
    return std::isnan(d) ? kInfinity : d;  // only one side is NaN here
}

void requireSameShape(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw Error("images differ in shape: " + shape(a) + " vs " + shape(b));
}

ImageDiff compareImages(const Image& a, const Image& b, const std::vector<double>& thresholds, const PixelMask* mask) {
    requireSameShape(a, b);
    requireMaskOf(a, mask);
    ImageDiff diff;
    diff.width = a.width;
    diff.height = a.height;
    diff.thresholds = thresholds;
    diff.pixels = mask ? mask->count : static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
    diff.mask = mask ? mask->description : kAllPixels;
    std::vector<double> sum(a.channels, 0.0), sumOfSquares(a.channels, 0.0);
    for (int c = 0; c < a.channels; ++c) {
        ChannelDiff channel;
        channel.name = a.channelNames.at(c);
        channel.countAbove.assign(thresholds.size(), 0);
        diff.channels.push_back(std::move(channel));
    }
    diff.pixelsAbove.assign(thresholds.size(), 0);
    double pixelLargest = 0;  // the largest error over the channels of the pixel being visited
    forEachError(a, b, mask, [&](int c, int x, int y, double error) {
        ChannelDiff& channel = diff.channels[c];
        pixelLargest = c == 0 ? error : std::max(pixelLargest, error);
        if (c + 1 == a.channels)
            for (std::size_t t = 0; t < thresholds.size(); ++t) diff.pixelsAbove[t] += pixelLargest > thresholds[t];
        sum[c] += error;
        sumOfSquares[c] += error * error;
        if (error > channel.maxAbs) {
            channel.maxAbs = error;
            channel.maxX = x;
            channel.maxY = y;
        }
        for (std::size_t t = 0; t < thresholds.size(); ++t)
            if (error > thresholds[t]) ++channel.countAbove[t];
    });
    const double pixels = std::max(static_cast<double>(diff.pixels), 1.0);  // a mask of no pixel: all zero
    for (int c = 0; c < a.channels; ++c) {
        ChannelDiff& channel = diff.channels[c];
        channel.meanAbs = sum[c] / pixels;
        channel.rmse = std::sqrt(sumOfSquares[c] / pixels);
        for (std::uint64_t count : channel.countAbove)
            channel.percentAbove.push_back(100.0 * static_cast<double>(count) / pixels);
    }
    return diff;
}

Image differenceImage(const Image& a, const Image& b, double scale) {
    requireSameShape(a, b);
    Image difference(a.width, a.height, a.channels);
    difference.channelNames = a.channelNames;
    std::size_t i = 0;
    forEachError(a, b, nullptr, [&](int, int, int, double error) { difference.pixels[i++] = static_cast<float>(error * scale); });
    return difference;
}

Image comparisonLayers(const Image& a, const Image& b) {
    const Image error = differenceImage(a, b);
    const int n = a.channels;
    Image layers(a.width, a.height, static_cast<int>(checkedCount("comparison layers", {3, std::uint64_t(n)}, 1024, "channels")));
    layers.channelNames.clear();
    for (const char* layer : {"reference.", "test.", "error."})
        for (const std::string& name : a.channelNames) layers.channelNames.push_back(layer + name);
    for (std::size_t p = 0; p < std::size_t(a.width) * std::size_t(a.height); ++p)
        for (int c = 0; c < n; ++c) {
            const std::size_t from = p * std::size_t(n) + std::size_t(c), to = p * std::size_t(3 * n) + std::size_t(c);
            layers.pixels[to] = a.pixels[from];
            layers.pixels[to + std::size_t(n)] = b.pixels[from];
            layers.pixels[to + std::size_t(2 * n)] = error.pixels[from];
        }
    return layers;
}

double ErrorHistogram::binLower(std::size_t bin) const { return bin < 2 ? 0.0 : edges.at(bin - 2); }

double ErrorHistogram::binUpper(std::size_t bin) const {
    if (bin == 0) return 0.0;
    return bin <= edges.size() ? edges[bin - 1] : kInfinity;
}

ErrorHistogram errorHistogram(const Image& a, const Image& b, std::vector<double> edges, const PixelMask* mask) {
    requireValidEdges(edges);
    requireSameShape(a, b);
    requireMaskOf(a, mask);
    ErrorHistogram histogram;
    histogram.edges = std::move(edges);
    histogram.channelNames = a.channelNames;
    histogram.pixels = mask ? mask->count : static_cast<std::uint64_t>(a.width) * static_cast<std::uint64_t>(a.height);
    histogram.counts.assign(a.channels, std::vector<std::uint64_t>(histogram.binCount(), 0));
    const std::vector<double>& e = histogram.edges;
    forEachError(a, b, mask, [&](int c, int, int, double error) {
        // The first edge >= error closes the bin (edge before, edge]; past the last edge, overflow.
        const std::size_t bin = error == 0.0 ? 0 : 1 + (std::lower_bound(e.begin(), e.end(), error) - e.begin());
        ++histogram.counts[c][bin];
    });
    return histogram;
}

std::vector<double> logBinEdges(double lo, double hi, int binsPerDecade) {
    if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi) || binsPerDecade < 1)
        throw Error("logarithmic bins need 0 < lo < hi and at least one bin per decade, got lo " + exactNumber(lo) +
                    ", hi " + exactNumber(hi) + ", " + std::to_string(binsPerDecade) + " per decade");
    const double firstExponent = std::log10(lo);
    // A histogram is a CSV row per bin: a million bins are plenty, and keep k well inside an int.
    requireWithin("logarithmic bins from " + exactNumber(lo) + " to " + exactNumber(hi) + " at " +
                      std::to_string(binsPerDecade) + " per decade",
                  std::ceil((std::log10(hi) - firstExponent) * binsPerDecade), 1e6, "bins");
    std::vector<double> edges{lo};
    for (int k = 1;; ++k) {
        const double edge = std::pow(10.0, firstExponent + static_cast<double>(k) / binsPerDecade);
        // Stop short of hi, also when rounding lands a hair below it: hi itself closes the list.
        if (edge >= hi * (1.0 - 1e-9)) break;
        edges.push_back(edge);
    }
    edges.push_back(hi);
    return edges;
}

std::string toCsv(const ErrorHistogram& histogram) {
    // Appends one cell at a time (also sidesteps a false -Wrestrict warning of GCC 12 on "," + s).
    std::string csv = "bin_lo,bin_hi";
    const auto cell = [&csv](const std::string& text) {
        csv += ',';
        csv += text;
    };
    for (const std::string& name : histogram.channelNames) cell(name);
    csv += '\n';
    for (std::size_t bin = 0; bin < histogram.binCount(); ++bin) {
        csv += exactNumber(histogram.binLower(bin));
        cell(exactNumber(histogram.binUpper(bin)));
        for (const auto& counts : histogram.counts) cell(std::to_string(counts[bin]));
        csv += '\n';
    }
    return csv;
}

}  // namespace vri
