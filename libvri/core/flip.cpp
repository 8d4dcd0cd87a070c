#include "libvri/core/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri {

namespace {

// The LDR-FLIP paper's constants.
constexpr float kColourExponent = 0.7f;    // q_c: the HyAB distance is raised to it
constexpr float kColourKnee = 0.4f;        // p_c: the fraction of the largest distance where compression starts
constexpr float kColourKneeError = 0.95f;  // p_t: the error given to that distance
constexpr double kFeatureWidth = 0.082;    // w: the width of the edges and points detected, in degrees
constexpr float kFeatureExponent = 0.5f;   // q_f: the feature difference is raised to it

// The contrast sensitivity of an opponent channel, from the paper's colour pipeline (spatial filtering):
// a sum of Gaussians a exp(-b rho^2) of the frequency rho in cycles per degree, which in space is
// a sqrt(pi / b) exp(-pi^2 r^2 / b) of the distance r in degrees. The achromatic and red-green channels
// have one term, the blue-yellow channel two.
struct CsfTerm {
    double a, b;
};
constexpr CsfTerm kCsfAchromatic{1.0, 0.0047};
constexpr CsfTerm kCsfRedGreen{1.0, 0.0053};
constexpr std::array<CsfTerm, 2> kCsfBlueYellow{{{34.1, 0.04}, {13.5, 0.025}}};
// The widest term's b: a term is a Gaussian of standard deviation sqrt(b / (2 pi^2)) degrees, and every
// filter reaches 3 of the widest's, as the reference implementation's.
constexpr double kCsfWidestB = 0.04;
// Beyond this radius a filter would cost hours per image: the viewing conditions are then a mistake.
constexpr double kMaxFilterRadius = 4096;

// Linear sRGB to CIE XYZ for the D65 white, the matrix of the reference implementation, exactly as the
// ratios of integers it gives. Its row sums are the white point, (0.950428545, 1, 1.088900371).
constexpr double kRgbToXyz[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                                    {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                                    {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};

using Matrix = std::array<std::array<float, 3>, 3>;
using Vec3 = std::array<float, 3>;

Vec3 product(const Matrix& m, const Vec3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// CIELAB's companding: the cube root above (6/29)^3, the line tangent to it below. The root as a power, as
// the reference implementation's (and faster than cbrt).
float labCompand(float t) {
    constexpr float delta = 6.0f / 29.0f;
    return t > delta * delta * delta ? std::pow(t, 1.0f / 3.0f) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

// The colour spaces of the pipeline, from the matrix above: computed in double, kept in float.
struct ColourSpaces {
    Matrix rgbToXyz{}, xyzToRgb{};
    Vec3 white{}, inverseWhite{};

    ColourSpaces() {
        const auto& m = kRgbToXyz;
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        for (int i = 0; i < 3; ++i) {
            white[i] = static_cast<float>(m[i][0] + m[i][1] + m[i][2]);
            inverseWhite[i] = static_cast<float>(1.0 / (m[i][0] + m[i][1] + m[i][2]));
            for (int j = 0; j < 3; ++j) {
                rgbToXyz[i][j] = static_cast<float>(m[i][j]);
                // The inverse is the transposed cofactor matrix over the determinant.
                const int r1 = (j + 1) % 3, r2 = (j + 2) % 3, c1 = (i + 1) % 3, c2 = (i + 2) % 3;
                xyzToRgb[i][j] = static_cast<float>((m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det);
            }
        }
    }

    // YCxCz (Zhang and Wandell's S-CIELAB opponent space): CIELAB's lightness and opponent axes without
    // the cube root, so that the contrast sensitivity filters act on values linear in light.
    Vec3 ycxczOfRgb(const Vec3& rgb) const {
        const Vec3 xyz = product(rgbToXyz, rgb);
        const float x = xyz[0] * inverseWhite[0], y = xyz[1] * inverseWhite[1], z = xyz[2] * inverseWhite[2];
        return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
    }

    Vec3 rgbOfYcxcz(const Vec3& ycxcz) const {
        const float y = (ycxcz[0] + 16.0f) / 116.0f;
        return product(xyzToRgb,
                       {(y + ycxcz[1] / 500.0f) * white[0], y * white[1], (y - ycxcz[2] / 200.0f) * white[2]});
    }

    // L*a*b* with the Hunt effect (colourfulness grows with lightness) folded in, as the paper's colour
    // pipeline: a* and b* scaled by 0.01 L*.
    Vec3 huntLabOfRgb(const Vec3& rgb) const {
        const Vec3 xyz = product(rgbToXyz, rgb);
        const float fx = labCompand(xyz[0] * inverseWhite[0]), fy = labCompand(xyz[1] * inverseWhite[1]),
                    fz = labCompand(xyz[2] * inverseWhite[2]);
        const float l = 116.0f * fy - 16.0f;
        return {l, 0.01f * l * (500.0f * (fx - fy)), 0.01f * l * (200.0f * (fy - fz))};
    }
};

// HyAB (Abasi, Amani Tehran and Fairchild): city-block in lightness, Euclidean in the opponent plane,
// which follows large colour differences better than a Euclidean distance throughout.
float hyab(const Vec3& a, const Vec3& b) {
    const float da = a[1] - b[1], db = a[2] - b[2];
    return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

const ColourSpaces& colourSpaces() {
    static const ColourSpaces spaces;
    return spaces;
}

// The largest colour distance, raised to q_c, that compression maps to 1: pure green against pure blue.
float largestColourDistance() {
    static const float d =
        std::pow(hyab(colourSpaces().huntLabOfRgb({0, 1, 0}), colourSpaces().huntLabOfRgb({0, 0, 1})), kColourExponent);
    return d;
}

// The paper's error redistribution, of a distance and the largest: distances up to p_c of the largest
// take the errors [0, p_t], which spreads the small differences that matter most over most of the range;
// the rest share (p_t, 1].
float compressedColourError(float distance, float top) {
    const float e = std::pow(distance, kColourExponent);
    const float knee = kColourKnee * top;
    return e < knee ? e * (kColourKneeError / knee)
                    : kColourKneeError + ((e - knee) / (top - knee)) * (1.0f - kColourKneeError);
}

// A float image of one channel, row 0 at the top.
struct Plane {
    int width = 0, height = 0;
    std::vector<float> values;

    Plane(int w, int h) : width(w), height(h), values(static_cast<std::size_t>(w) * h) {}
    float* row(int y) { return values.data() + static_cast<std::size_t>(y) * width; }
    const float* row(int y) const { return values.data() + static_cast<std::size_t>(y) * width; }
};

using Planes3 = std::array<Plane, 3>;

// A 1D filter of odd length, its centre at index size / 2.
using Taps = std::vector<float>;

// Each row convolved with `taps`: out(x) = sum over k of taps[k] in(x + k - r), r the radius, the pixels
// beyond the row's ends repeating its end pixels (clamp to edge, as the reference implementation's),
// summed in the order k = 0, 1, .. as the reference's. The taps loop outside so that the inner loop runs
// over contiguous pixels and vectorises.
Plane filterRows(const Plane& in, const Taps& taps) {
    const int r = static_cast<int>(taps.size() / 2);
    Plane out(in.width, in.height);
    std::vector<float> padded(static_cast<std::size_t>(in.width) + 2 * r);
    for (int y = 0; y < in.height; ++y) {
        const float* src = in.row(y);
        for (std::size_t i = 0; i < padded.size(); ++i)
            padded[i] = src[std::clamp(static_cast<int>(i) - r, 0, in.width - 1)];
        float* o = out.row(y);
        for (std::size_t k = 0; k < taps.size(); ++k) {
            const float w = taps[k];
            const float* p = padded.data() + k;
            for (int x = 0; x < in.width; ++x) o[x] += w * p[x];
        }
    }
    return out;
}

// Each column convolved with `taps`, as filterRows.
Plane filterColumns(const Plane& in, const Taps& taps) {
    const int r = static_cast<int>(taps.size() / 2);
    Plane out(in.width, in.height);
    for (int y = 0; y < in.height; ++y) {
        float* o = out.row(y);
        for (std::size_t k = 0; k < taps.size(); ++k) {
            const float w = taps[k];
            const float* p = in.row(std::clamp(y + static_cast<int>(k) - r, 0, in.height - 1));
            for (int x = 0; x < in.width; ++x) o[x] += w * p[x];
        }
    }
    return out;
}

Plane separable(const Plane& in, const Taps& alongRows, const Taps& alongColumns) {
    return filterColumns(filterRows(in, alongRows), alongColumns);
}

// The filters of both pipelines for one viewing distance.
struct Filters {
    // The contrast sensitivity filters, separated as 2D kernel = rows x columns. A single Gaussian term
    // separates exactly into its 1D Gaussian, normalised to sum 1. The blue-yellow sum of two terms,
    // K(x, y) = sum_i A_i exp(-pi^2 (x^2 + y^2) / b_i), separates term by term into h_i(x) h_i(y) with
    // h_i = sqrt(A_i) exp(-pi^2 x^2 / b_i); scaled by 1 / sqrt(sum_i (sum h_i)^2), the 2D kernel sums to 1.
    Taps achromatic, redGreen;
    std::array<Taps, 2> blueYellow;
    // The feature detectors: a Gaussian g of standard deviation w / 2 degrees, normalised to sum 1, and
    // its first and second derivatives, each normalised so that its positive taps sum to 1 and its
    // negative ones to -1 (the paper's feature pipeline). The 2D edge detector along x is
    // firstDerivative(x) gaussian(y), whose positive and negative parts still sum to 1 and -1.
    Taps gaussian, firstDerivative, secondDerivative;
};

// f(k) at the pixel offsets k = -radius .. radius.
template <class F>
std::vector<double> sampled(int radius, F f) {
    std::vector<double> out;
    for (int k = -radius; k <= radius; ++k) out.push_back(f(k));
    return out;
}

double sumOf(const std::vector<double>& values) { return std::accumulate(values.begin(), values.end(), 0.0); }

Taps scaled(const std::vector<double>& taps, double scale) {
    Taps out;
    for (double t : taps) out.push_back(static_cast<float>(t * scale));
    return out;
}

// Scaled so that the positive taps sum to 1 and the negative ones to -1.
Taps balanced(const std::vector<double>& taps) {
    double positive = 0, negative = 0;
    for (double t : taps) (t > 0 ? positive : negative) += std::abs(t);
    Taps out;
    for (double t : taps) out.push_back(static_cast<float>(t / (t > 0 ? positive : negative)));
    return out;
}

Filters filtersFor(double ppd) {
    constexpr double pi = std::numbers::pi;
    const double radiusInDegrees = 3.0 * std::sqrt(kCsfWidestB / (2.0 * pi * pi));
    requireWithin("FLIP's filters at " + std::to_string(ppd) + " pixels per degree", radiusInDegrees * ppd,
                  kMaxFilterRadius, "pixels of radius");
    const int csfRadius = static_cast<int>(std::ceil(radiusInDegrees * ppd));
    // A term's exp(-pi^2 x^2 / b) along one direction: along x times along y is the radial 2D term.
    const auto profile = [&](const CsfTerm& t) {
        return sampled(csfRadius, [&](int k) { return std::exp(-pi * pi * (k / ppd) * (k / ppd) / t.b); });
    };
    Filters f;
    // One term: its amplitude a sqrt(pi / b) cancels in the normalisation.
    const std::vector<double> achromatic = profile(kCsfAchromatic), redGreen = profile(kCsfRedGreen);
    f.achromatic = scaled(achromatic, 1.0 / sumOf(achromatic));
    f.redGreen = scaled(redGreen, 1.0 / sumOf(redGreen));
    std::array<std::vector<double>, 2> blueYellow;
    std::array<double, 2> root{}, sums{};  // sqrt(A_i), and the sums of h_i
    for (int i = 0; i < 2; ++i) {
        blueYellow[i] = profile(kCsfBlueYellow[i]);
        root[i] = std::sqrt(kCsfBlueYellow[i].a * std::sqrt(pi / kCsfBlueYellow[i].b));
        sums[i] = root[i] * sumOf(blueYellow[i]);
    }
    for (int i = 0; i < 2; ++i) f.blueYellow[i] = scaled(blueYellow[i], root[i] / std::hypot(sums[0], sums[1]));

    const double sigma = 0.5 * kFeatureWidth * ppd;  // pixels
    const int featureRadius = static_cast<int>(std::ceil(3.0 * sigma));
    const auto gaussian = [&](int k) { return std::exp(-k * k / (2.0 * sigma * sigma)); };
    const std::vector<double> g = sampled(featureRadius, gaussian);
    f.gaussian = scaled(g, 1.0 / sumOf(g));
    // The derivatives up to positive factors, which the balancing removes.
    f.firstDerivative = balanced(sampled(featureRadius, [&](int k) { return -k * gaussian(k); }));
    f.secondDerivative =
        balanced(sampled(featureRadius, [&](int k) { return (k * k / (sigma * sigma) - 1.0) * gaussian(k); }));
    return f;
}

// The image as the observer resolves it at this distance, in Hunt-adjusted L*a*b*: each opponent channel
// filtered by its contrast sensitivity, then back to linear RGB clamped to [0, 1] (the filters can leave
// the gamut) and on to L*a*b*.
Planes3 perceivedLab(const Planes3& ycxcz, const Filters& f) {
    Planes3 out{separable(ycxcz[0], f.achromatic, f.achromatic), separable(ycxcz[1], f.redGreen, f.redGreen),
                separable(ycxcz[2], f.blueYellow[0], f.blueYellow[0])};
    {
        const Plane second = separable(ycxcz[2], f.blueYellow[1], f.blueYellow[1]);
        for (std::size_t p = 0; p < second.values.size(); ++p) out[2].values[p] += second.values[p];
    }
    const ColourSpaces& s = colourSpaces();
    for (std::size_t p = 0; p < out[0].values.size(); ++p) {
        Vec3 rgb = s.rgbOfYcxcz({out[0].values[p], out[1].values[p], out[2].values[p]});
        for (float& c : rgb) c = std::clamp(c, 0.0f, 1.0f);
        const Vec3 lab = s.huntLabOfRgb(rgb);
        for (int c = 0; c < 3; ++c) out[c].values[p] = lab[c];
    }
    return out;
}

// The paper's feature pipeline on YCxCz's lightness brought to [0, 1] (which `lightness` becomes): per
// pixel, the edge strength, the length of the (x, y) pair of first-derivative responses, and the point
// strength, that of the second-derivative responses. Each response is in [-1, 1], a strength in [0, sqrt(2)].
struct Features {
    Plane edge, point;
};

Features features(Plane& lightness, const Filters& f) {
    for (float& v : lightness.values) v = v * (1.0f / 116.0f) + 16.0f / 116.0f;
    const Plane smoothRows = filterRows(lightness, f.gaussian);
    Features out{filterColumns(filterRows(lightness, f.firstDerivative), f.gaussian),
                 filterColumns(filterRows(lightness, f.secondDerivative), f.gaussian)};
    const Plane dy = filterColumns(smoothRows, f.firstDerivative), ddy = filterColumns(smoothRows, f.secondDerivative);
    for (std::size_t p = 0; p < dy.values.size(); ++p) {
        const float dx = out.edge.values[p], ddx = out.point.values[p];
        out.edge.values[p] = std::sqrt(dx * dx + dy.values[p] * dy.values[p]);
        out.point.values[p] = std::sqrt(ddx * ddx + ddy.values[p] * ddy.values[p]);
    }
    return out;
}

// LDR-FLIP of two linear RGB images with values in [0, 1], which become YCxCz here.
Plane ldrErrorMap(Planes3& reference, Planes3& test, const Filters& filters) {
    const ColourSpaces& s = colourSpaces();
    for (Planes3* image : {&reference, &test})
        for (std::size_t p = 0; p < (*image)[0].values.size(); ++p) {
            const Vec3 v = s.ycxczOfRgb({(*image)[0].values[p], (*image)[1].values[p], (*image)[2].values[p]});
            for (int c = 0; c < 3; ++c) (*image)[c].values[p] = v[c];
        }
    Plane error(reference[0].width, reference[0].height);
    {
        const Planes3 a = perceivedLab(reference, filters), b = perceivedLab(test, filters);
        const float top = largestColourDistance();
        for (std::size_t p = 0; p < error.values.size(); ++p)
            error.values[p] = compressedColourError(hyab({a[0].values[p], a[1].values[p], a[2].values[p]},
                                                         {b[0].values[p], b[1].values[p], b[2].values[p]}),
                                                    top);
    }
    const Features a = features(reference[0], filters), b = features(test[0], filters);
    // The feature difference, brought to [0, 1] and raised to q_f: as it nears 1 it lifts the colour error
    // towards 1 (the paper's final error).
    const float toUnit = 1.0f / std::sqrt(2.0f);
    for (std::size_t p = 0; p < error.values.size(); ++p) {
        const float edge = std::abs(a.edge.values[p] - b.edge.values[p]);
        const float point = std::abs(a.point.values[p] - b.point.values[p]);
        const float feature = std::pow(toUnit * std::max(edge, point), kFeatureExponent);
        error.values[p] = std::pow(error.values[p], 1.0f - feature);
    }
    return error;
}

// The most float planes of width x height alive at once: HDR-FLIP's inputs (6) and running maximum (1)
// beside LDR-FLIP's 15 at its peak (its inputs, 6, the error, one perceived image's 3 and the other's 5
// while it is filtered).
constexpr int kMostPlanes = 22;

// Checks what both variants need: equal sizes, a mask of theirs, and viewing conditions that make sense.
void requireComparable(const char* what, const Image& reference, const Image& test, const FlipViewing& viewing,
                       const PixelMask* mask) {
    if (reference.width != test.width || reference.height != test.height)
        throw Error(std::string(what) + ": the images differ in size: " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " vs " + std::to_string(test.width) + "x" +
                    std::to_string(test.height));
    imageBytes(reference.width, reference.height, kMostPlanes);
    const std::size_t pixels = static_cast<std::size_t>(reference.width) * reference.height;
    if (mask && mask->keep.size() != pixels)
        throw Error(std::string(what) + ": the mask has " + std::to_string(mask->keep.size()) + " pixels, the images " +
                    std::to_string(pixels));
    for (double v : {viewing.monitorDistance, viewing.monitorWidth, viewing.monitorPixelsWide})
        if (!(v > 0 && std::isfinite(v)))
            throw Error(std::string(what) + ": the monitor's distance, width and pixels must be positive, got " +
                        std::to_string(viewing.monitorDistance) + " m, " + std::to_string(viewing.monitorWidth) +
                        " m, " + std::to_string(viewing.monitorPixelsWide) + " pixels");
}

// The image's R, G and B channels as planes; throws when one is missing or holds a value that is not finite.
Planes3 rgbPlanes(const Image& image, const std::string& what) {
    Planes3 out{Plane(image.width, image.height), Plane(image.width, image.height), Plane(image.width, image.height)};
    static const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const int from = channelIndex(image, names[c]);
        if (from < 0) {
            std::string has;
            for (const std::string& n : image.channelNames) has += (has.empty() ? "" : ",") + n;
            throw Error(what + " has no channel '" + names[c] + "' (it has " + has + ")");
        }
        for (std::size_t p = 0; p < out[c].values.size(); ++p) {
            const float v = image.pixels[p * image.channels + from];
            if (!std::isfinite(v))
                throw Error(what + "'s channel " + names[c] + " is " + std::to_string(v) + " at pixel " +
                            std::to_string(p % image.width) + "," + std::to_string(p / image.width));
            out[c].values[p] = v;
        }
    }
    return out;
}

// The q-quantile of `values` (not empty), linear between the sorted values around position q (n - 1);
// reorders them.
double quantile(std::vector<float>& values, double q) {
    const double position = q * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(position);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(below), values.end());
    const double low = values[below];
    if (below + 1 == values.size()) return low;
    const double high = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(below) + 1, values.end());
    return low + (position - static_cast<double>(below)) * (high - low);
}

FlipResult summarised(Plane&& error, const PixelMask* mask) {
    FlipResult result;
    result.width = error.width;
    result.height = error.height;
    result.errorMap = std::move(error.values);
    std::vector<float> kept;
    double total = 0;
    for (std::size_t p = 0; p < result.errorMap.size(); ++p) {
        if (mask && !mask->keep[p]) continue;
        kept.push_back(result.errorMap[p]);
        total += result.errorMap[p];
        result.max = std::max(result.max, static_cast<double>(result.errorMap[p]));
    }
    result.pixels = kept.size();
    if (kept.empty()) return result;
    result.mean = total / static_cast<double>(kept.size());
    result.p95 = quantile(kept, 0.95);
    result.median = quantile(kept, 0.5);
    return result;
}

// A tone curve as the ratio of two quadratics, (p0 x^2 + p1 x + p2) / (q0 x^2 + q1 x + q2), per channel.
struct ToneCurve {
    float p0, p1, p2, q0, q1, q2;
    float operator()(float x) const { return ((x * x) * p0 + x * p1 + p2) / (x * x * q0 + x * q1 + q2); }
};

// ACES as Narkowicz's fit, whose input is pre-exposed by 0.6: the 0.6 is folded into the coefficients so
// that the curve takes the linear values themselves. Hable's filmic curve as a rational fit. Reinhard's is
// x / (1 + luminance) per pixel; x / (1 + x) stands for it where one curve is needed (the exposure range).
ToneCurve toneCurve(FlipToneMapper toneMapper) {
    switch (toneMapper) {
    case FlipToneMapper::Aces:
        return {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};
    case FlipToneMapper::Hable: return {0.231683f, 0.013791f, 0.0f, 0.18f, 0.3f, 0.018f};
    case FlipToneMapper::Reinhard: break;
    }
    return {0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f};
}

float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

// The image exposed by `scale` and tone mapped into [0, 1].
Planes3 toneMapped(const Planes3& image, float scale, FlipToneMapper toneMapper) {
    Planes3 out = image;
    const ToneCurve curve = toneCurve(toneMapper);
    for (std::size_t p = 0; p < out[0].values.size(); ++p) {
        Vec3 c{out[0].values[p] * scale, out[1].values[p] * scale, out[2].values[p] * scale};
        if (toneMapper == FlipToneMapper::Reinhard) {
            const float factor = 1.0f / (1.0f + luminance(c[0], c[1], c[2]));
            for (float& v : c) v *= factor;
        } else {
            for (float& v : c) v = curve(v);
        }
        // A curve overflowing to inf / inf (a value near float's largest) gives NaN, taken as 0 as the
        // reference implementation's clamp does.
        for (int k = 0; k < 3; ++k) out[k].values[p] = c[k] > 0.0f ? std::min(c[k], 1.0f) : 0.0f;
    }
    return out;
}

// The input at which the tone curve reaches t = 0.85: the positive root of
// (p0 - t q0) x^2 + (p1 - t q1) x + (p2 - t q2) = 0. The constant term is negative and the square's
// positive (Reinhard's curve has none), so exactly one root is positive.
double exposedInput(FlipToneMapper toneMapper) {
    constexpr double t = 0.85;
    const ToneCurve c = toneCurve(toneMapper);
    const double a = c.p0 - t * c.q0, b = c.p1 - t * c.q1, k = c.p2 - t * c.q2;
    if (a == 0.0) return -k / b;
    const double half = -0.5 * b / a;
    return half + std::sqrt(half * half - k / a);
}

std::vector<float> luminances(const Planes3& image, const PixelMask* mask) {
    std::vector<float> out;
    for (std::size_t p = 0; p < image[0].values.size(); ++p)
        if (!mask || mask->keep[p])
            out.push_back(luminance(image[0].values[p], image[1].values[p], image[2].values[p]));
    return out;
}

double startExposure(const std::vector<float>& luminance, FlipToneMapper toneMapper) {
    const double brightest = luminance.empty() ? 0.0 : *std::max_element(luminance.begin(), luminance.end());
    if (!(brightest > 0))
        throw Error("HDR-FLIP: the reference's brightest luminance is " + std::to_string(brightest) +
                    ": there is no start exposure to compute");
    return std::log2(exposedInput(toneMapper) / brightest);
}

double stopExposure(std::vector<float>& luminance, FlipToneMapper toneMapper) {
    double median = 0;
    if (!luminance.empty()) {
        const auto middle = luminance.begin() + static_cast<std::ptrdiff_t>(luminance.size() / 2);
        std::nth_element(luminance.begin(), middle, luminance.end());
        median = *middle;
    }
    if (!(median > 0))
        throw Error("HDR-FLIP: the reference's median luminance is " + std::to_string(median) +
                    " (a black background?): there is no stop exposure to compute");
    return std::log2(exposedInput(toneMapper) / median);
}

// An exposure e multiplies by 2^e: beyond 2^126 either way, no longer a normal float.
constexpr double kMostExposure = 126;

FlipExposureRange withCount(double start, double stop, std::optional<int> count) {
    for (double e : {start, stop})
        if (!(std::abs(e) <= kMostExposure))
            throw Error("HDR-FLIP: the exposure " + std::to_string(e) + " is outside [-126, 126], the range of float");
    if (start > stop)
        throw Error("HDR-FLIP: the start exposure " + std::to_string(start) + " is above the stop exposure " +
                    std::to_string(stop));
    const int n = count ? *count : static_cast<int>(std::max(2.0, std::ceil(stop - start)));
    if (n < 2) throw Error("HDR-FLIP: the number of exposures must be at least 2, got " + std::to_string(n));
    return {start, stop, n};
}

}  // namespace

double FlipViewing::pixelsPerDegree() const {
    return monitorDistance * (monitorPixelsWide / monitorWidth) * (std::numbers::pi / 180.0);
}

FlipResult ldrFlip(const Image& reference, const Image& test, const FlipViewing& viewing, const PixelMask* mask) {
    requireComparable("LDR-FLIP", reference, test, viewing, mask);
    const Filters filters = filtersFor(viewing.pixelsPerDegree());
    return allocateOrExplain(
        "LDR-FLIP of " + std::to_string(reference.width) + "x" + std::to_string(reference.height) + " images",
        imageBytes(reference.width, reference.height, kMostPlanes), [&] {
            Planes3 a = rgbPlanes(reference, "LDR-FLIP: the reference");
            Planes3 b = rgbPlanes(test, "LDR-FLIP: the test image");
            for (Planes3* image : {&a, &b})
                for (Plane& plane : *image)
                    for (float& v : plane.values) v = std::clamp(v, 0.0f, 1.0f);
            return summarised(ldrErrorMap(a, b, filters), mask);
        });
}

FlipResult hdrFlip(const Image& reference, const Image& test, const FlipViewing& viewing, const PixelMask* mask,
                   const FlipHdrOptions& options) {
    requireComparable("HDR-FLIP", reference, test, viewing, mask);
    const Filters filters = filtersFor(viewing.pixelsPerDegree());
    return allocateOrExplain(
        "HDR-FLIP of " + std::to_string(reference.width) + "x" + std::to_string(reference.height) + " images",
        imageBytes(reference.width, reference.height, kMostPlanes), [&] {
            const Planes3 a = rgbPlanes(reference, "HDR-FLIP: the reference");
            const Planes3 b = rgbPlanes(test, "HDR-FLIP: the test image");
            double start = 0, stop = 0;
            {
                std::vector<float> luminance;
                if (!options.startExposure || !options.stopExposure) luminance = luminances(a, nullptr);
                start = options.startExposure ? *options.startExposure : startExposure(luminance, options.toneMapper);
                stop = options.stopExposure ? *options.stopExposure : stopExposure(luminance, options.toneMapper);
            }
            const FlipExposureRange range = withCount(start, stop, options.exposures);
            // The paper's HDR-FLIP: the largest LDR-FLIP error over the exposures, per pixel.
            Plane worst(reference.width, reference.height);
            const double step = (range.stop - range.start) / (range.count - 1);
            for (int i = 0; i < range.count; ++i) {
                const auto scale = static_cast<float>(std::exp2(range.start + i * step));
                Planes3 exposedA = toneMapped(a, scale, options.toneMapper);
                Planes3 exposedB = toneMapped(b, scale, options.toneMapper);
                const Plane error = ldrErrorMap(exposedA, exposedB, filters);
                for (std::size_t p = 0; p < worst.values.size(); ++p)
                    worst.values[p] = std::max(worst.values[p], error.values[p]);
            }
            FlipResult result = summarised(std::move(worst), mask);
            result.exposures = range;
            return result;
        });
}

FlipExposureRange flipExposureRange(const Image& reference, FlipToneMapper toneMapper, const PixelMask* mask) {
    imageBytes(reference.width, reference.height, 4);
    if (mask && mask->keep.size() != static_cast<std::size_t>(reference.width) * reference.height)
        throw Error("HDR-FLIP: the mask has " + std::to_string(mask->keep.size()) + " pixels, the image " +
                    std::to_string(static_cast<std::size_t>(reference.width) * reference.height));
    std::vector<float> luminance = luminances(rgbPlanes(reference, "HDR-FLIP: the reference"), mask);
    const double start = startExposure(luminance, toneMapper);
    return withCount(start, stopExposure(luminance, toneMapper), std::nullopt);
}

}  // namespace vri
