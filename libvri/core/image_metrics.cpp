#include "libvri/core/image_metrics.h"

#include <array>
#include <cmath>
#include <limits>

#include "libvri/core/image_compare.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/util/error.h"

namespace vri {

namespace {

constexpr int kWindow = 11;        // SSIM's Gaussian window, 11 x 11
constexpr double kSigma = 1.5;     // its standard deviation in pixels
constexpr double kC1 = 0.01 * 0.01;  // (K1 L)^2 with K1 = 0.01, L = 1
constexpr double kC2 = 0.03 * 0.03;  // (K2 L)^2 with K2 = 0.03

// The normalised 1D Gaussian: the 2D window is the outer product of it with itself, whose sum is 1 too.
std::array<double, kWindow> gaussianWeights() {
    std::array<double, kWindow> g{};
    double sum = 0;
    for (int k = 0; k < kWindow; ++k) {
        const double d = k - kWindow / 2;
        g[k] = std::exp(-d * d / (2 * kSigma * kSigma));
        sum += g[k];
    }
    for (double& w : g) w /= sum;
    return g;
}

// The Gaussian-weighted mean of `values` (width x height) over each window that fits in the image: the
// window at (x, y) covers [x, x + 11) x [y, y + 11). Separable: rows first, then columns.
std::vector<double> windowMeans(const std::vector<double>& values, int width, int height) {
    static const std::array<double, kWindow> g = gaussianWeights();
    const int w = width - kWindow + 1, h = height - kWindow + 1;
    std::vector<double> rows(static_cast<std::size_t>(w) * height), out(static_cast<std::size_t>(w) * h);
    // The taps outside, the pixels of a row inside: the inner loops run over contiguous memory and vectorise,
    // and each output still sums its taps in the order k = 0 .. 10.
    for (int y = 0; y < height; ++y) {
        const double* in = values.data() + static_cast<std::size_t>(y) * width;
        double* row = rows.data() + static_cast<std::size_t>(y) * w;
        for (int k = 0; k < kWindow; ++k)
            for (int x = 0; x < w; ++x) row[x] += g[k] * in[x + k];
    }
    for (int y = 0; y < h; ++y) {
        double* o = out.data() + static_cast<std::size_t>(y) * w;
        for (int k = 0; k < kWindow; ++k) {
            const double* row = rows.data() + static_cast<std::size_t>(y + k) * w;
            for (int x = 0; x < w; ++x) o[x] += g[k] * row[x];
        }
    }
    return out;
}

// Channel c's SSIM over the windows whose centre the mask keeps; NaN when no window fits or none is kept.
double ssimOfChannel(const Image& a, const Image& b, int c, const PixelMask* mask, std::uint64_t* windows) {
    const int width = a.width, height = a.height;
    *windows = 0;
    if (width < kWindow || height < kWindow) return std::numeric_limits<double>::quiet_NaN();
    const std::size_t n = static_cast<std::size_t>(width) * height;
    std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
    for (std::size_t p = 0; p < n; ++p) {
        x[p] = a.pixels[p * a.channels + c];
        y[p] = b.pixels[p * b.channels + c];
        xx[p] = x[p] * x[p];
        yy[p] = y[p] * y[p];
        xy[p] = x[p] * y[p];
    }
    const std::vector<double> mx = windowMeans(x, width, height), my = windowMeans(y, width, height),
                              mxx = windowMeans(xx, width, height), myy = windowMeans(yy, width, height),
                              mxy = windowMeans(xy, width, height);
    const int w = width - kWindow + 1, h = height - kWindow + 1;
    double sum = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const std::size_t centre = static_cast<std::size_t>(j + kWindow / 2) * width + i + kWindow / 2;
            if (mask && !mask->keep[centre]) continue;
            const std::size_t q = static_cast<std::size_t>(j) * w + i;
            const double sxx = mxx[q] - mx[q] * mx[q], syy = myy[q] - my[q] * my[q], sxy = mxy[q] - mx[q] * my[q];
            sum += ((2 * mx[q] * my[q] + kC1) * (2 * sxy + kC2)) /
                   ((mx[q] * mx[q] + my[q] * my[q] + kC1) * (sxx + syy + kC2));
            ++*windows;
        }
    return *windows > 0 ? sum / static_cast<double>(*windows) : std::numeric_limits<double>::quiet_NaN();
}

double psnrOf(double mse) {
    return mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(kPsnrPeak * kPsnrPeak / mse);
}

void addFlip(ImageMetrics& m, const Image& reference, const Image& test, const PixelMask* mask, bool withHdrFlip) {
    for (const char* name : {"R", "G", "B"})
        if (channelIndex(reference, name) < 0) {
            m.flipUnavailable = "FLIP compares colours: the images have no " + std::string(name) + " channel";
            return;
        }
    for (const Image* image : {&reference, &test})
        for (const char* name : {"R", "G", "B"})
            for (std::size_t i = std::size_t(channelIndex(*image, name)); i < image->pixels.size(); i += std::size_t(image->channels))
                if (!std::isfinite(image->pixels[i])) {
                    m.flipUnavailable = "FLIP needs finite colours: an image holds a NaN or an infinity in R, G or B";
                    return;
                }
    m.ldrFlip = ldrFlip(reference, test, {}, mask);
    m.ldrFlip->errorMap = {};
    if (!withHdrFlip) return;
    try {
        // The pixels either image hits, where the images have an alpha channel; else all of them.
        const PixelMask hit = channelIndex(reference, "A") == reference.channels - 1 ? alphaMask(reference, test, 0.0)
                                                                                  : fullMask(reference.width, reference.height);
        FlipHdrOptions options;
        const FlipExposureRange range = flipExposureRange(reference, options.toneMapper, &hit);
        options.startExposure = range.start;
        options.stopExposure = range.stop;
        options.exposures = range.count;
        m.hdrFlip = hdrFlip(reference, test, {}, mask, options);
        m.hdrFlip->errorMap = {};
    } catch (const Error& e) {
        m.flipUnavailable = e.what();  // "HDR-FLIP: ..."
    }
}

}  // namespace

ImageMetrics imageMetrics(const Image& reference, const Image& test, const PixelMask* mask, bool withHdrFlip) {
    requireSameShape(reference, test);
    const std::size_t pixels = static_cast<std::size_t>(reference.width) * reference.height;
    if (mask && mask->keep.size() != pixels) throw Error("the mask is not the images' size");
    const int channels = reference.channels;
    ImageMetrics m;
    m.channelNames = reference.channelNames;
    m.pixels = mask ? mask->count : pixels;
    std::vector<double> squared(channels, 0), relative(channels, 0), smape(channels, 0);
    for (std::size_t p = 0; p < pixels; ++p) {
        if (mask && !mask->keep[p]) continue;
        for (int c = 0; c < channels; ++c) {
            const float a = reference.pixels[p * channels + c], b = test.pixels[p * channels + c];
            const double e = absoluteError(a, b);
            squared[c] += e * e;
            relative[c] += e * e / (static_cast<double>(a) * a + kRelativeEpsilon);
            smape[c] += e / (std::abs(static_cast<double>(a)) + std::abs(static_cast<double>(b)) + kRelativeEpsilon);
        }
    }
    const double count = std::max(static_cast<double>(m.pixels), 1.0);
    double allSquared = 0, allRelative = 0, allSmape = 0, allSsim = 0;
    for (int c = 0; c < channels; ++c) {
        MetricValues v;
        v.psnr = psnrOf(squared[c] / count);
        v.relMse = relative[c] / count;
        v.smape = smape[c] / count;
        v.ssim = ssimOfChannel(reference, test, c, mask, &m.ssimWindows);
        allSquared += squared[c];
        allRelative += relative[c];
        allSmape += smape[c];
        allSsim += v.ssim;
        m.channels.push_back(v);
    }
    m.all.psnr = psnrOf(allSquared / (count * channels));
    m.all.relMse = allRelative / (count * channels);
    m.all.smape = allSmape / (count * channels);
    m.all.ssim = allSsim / channels;
    addFlip(m, reference, test, mask, withHdrFlip);
    return m;
}

}  // namespace vri
