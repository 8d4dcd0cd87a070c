// FLIP (libvri/core/flip.h) against the authors' reference implementation (NVlabs/flip v1.6), on the image
// pairs of tests/data/flip, whose README.txt says where they and the expected values come from; and the
// properties any error map must have.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include "libvri/core/flip.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/io/image_io.h"
#include "libvri/util/error.h"

namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(VRI_TEST_DATA_DIR) / "flip";

// The reference's values are means of its float error maps, in double. vri's differ from them by about 1e-8
// (its filters and colour matrices are computed in double, then rounded to float: a few pixels differ in
// the last bits, the largest by 7e-6); a filter radius off by one pixel moves the mean by 2.4e-6 and p_t
// off by 1e-4 by 8e-6, which these tolerances catch. Single pixels (the max) get the per-pixel bound.
constexpr double kMeanTolerance = 2e-7;
constexpr double kPixelTolerance = 5e-5;
constexpr double kExposureTolerance = 1e-5;  // the reference computes the range in float

// The sRGB decoding (IEC 61966-2-1) of a PNG's byte / 255, as the reference tool decodes its LDR inputs.
vri::Image linearFromSrgb(vri::Image image) {
    for (float& v : image.pixels) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    return image;
}

// A w x h RGB image whose pixel (x, y) is colour(x, y).
template <class Colour>
vri::Image rgbImage(int w, int h, Colour colour) {
    vri::Image image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto c = colour(x, y);
            for (int k = 0; k < 3; ++k) image.at(x, y, k) = c[k];
        }
    return image;
}

// A small pair with edges, colour and a few wrong pixels: a chequered gradient, and the same with a tint
// and three fireflies.
struct SmallPair {
    vri::Image reference = rgbImage(40, 30, [](int x, int y) {
        const float v = ((x / 5 + y / 5) % 2 ? 0.8f : 0.2f) * (0.5f + x / 80.0f);
        return std::array<float, 3>{v, 0.5f * v, 0.25f + 0.5f * y / 30.0f};
    });
    vri::Image test = reference;
    SmallPair() {
        for (int y = 0; y < 30; ++y)
            for (int x = 20; x < 40; ++x) test.at(x, y, 1) *= 0.8f;
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) test.at(5 + 11 * i, 4 + 9 * i, k) = 1.0f;
    }
};

double meanOver(const std::vector<float>& values, const vri::PixelMask& mask) {
    double sum = 0;
    for (std::size_t p = 0; p < values.size(); ++p)
        if (mask.keep[p]) sum += values[p];
    return sum / static_cast<double>(mask.count);
}

}  // namespace

TEST_CASE("FLIP: pixels per degree of the papers' monitor, 0.7 m wide, 3840 pixels, at 0.7 m") {
    CHECK(vri::FlipViewing{}.pixelsPerDegree() == doctest::Approx(67.0206433).epsilon(1e-9));
    CHECK(vri::FlipViewing{1.4, 0.7, 3840}.pixelsPerDegree() == doctest::Approx(2 * 67.0206433).epsilon(1e-9));
}

TEST_CASE("FLIP: LDR-FLIP of the test pair as the reference implementation computes it") {
    const vri::Image reference = linearFromSrgb(vri::readImage(kData / "ldr_reference.png"));
    const vri::Image test = linearFromSrgb(vri::readImage(kData / "ldr_test.png"));
    const vri::FlipResult flip = vri::ldrFlip(reference, test);
    CHECK(flip.width == 256);
    CHECK(flip.height == 192);
    CHECK(flip.pixels == 256 * 192);
    CHECK(std::abs(flip.mean - 0.0843408088519) <= kMeanTolerance);
    CHECK(std::abs(flip.max - 0.635420144) <= kPixelTolerance);
    CHECK(flip.exposures.count == 0);
    // The median and 95th percentile as flip.h defines them (the reference reports weighted quartiles).
    std::vector<float> sorted = flip.errorMap;
    std::sort(sorted.begin(), sorted.end());
    const double position = 0.95 * static_cast<double>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(position);
    CHECK(flip.p95 == doctest::Approx(sorted[below] + (position - below) * (sorted[below + 1] - sorted[below])));
    CHECK(flip.median == doctest::Approx(0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2])));
}

TEST_CASE("FLIP: HDR-FLIP of the test pair, for each tone curve, as the reference implementation computes it") {
    const vri::Image reference = vri::readImage(kData / "hdr_reference.exr");
    const vri::Image test = vri::readImage(kData / "hdr_test.exr");
    struct Expected {
        vri::FlipToneMapper toneMapper;
        double mean, max, start, stop;
    };
    const Expected cases[] = {{vri::FlipToneMapper::Aces, 0.1256706515, 0.988334119, -1.74180067, 7.9391284},
                              {vri::FlipToneMapper::Hable, 0.107252927831, 0.988039553, -1.17997265, 8.50095654},
                              {vri::FlipToneMapper::Reinhard, 0.131041497698, 0.983691752, -0.322597235, 9.35833168}};
    for (const Expected& e : cases) {
        CAPTURE(static_cast<int>(e.toneMapper));
        vri::FlipHdrOptions options;
        options.toneMapper = e.toneMapper;
        const vri::FlipResult flip = vri::hdrFlip(reference, test, {}, nullptr, options);
        CHECK(std::abs(flip.mean - e.mean) <= kMeanTolerance);
        CHECK(std::abs(flip.max - e.max) <= kPixelTolerance);
        CHECK(std::abs(flip.exposures.start - e.start) <= kExposureTolerance);
        CHECK(std::abs(flip.exposures.stop - e.stop) <= kExposureTolerance);
        CHECK(flip.exposures.count == 10);
        const vri::FlipExposureRange range = vri::flipExposureRange(reference, e.toneMapper);
        CHECK(range.start == flip.exposures.start);
        CHECK(range.stop == flip.exposures.stop);
        CHECK(range.count == 10);
    }
}

TEST_CASE("FLIP: identical images differ by 0 everywhere; every error is in [0, 1]") {
    const SmallPair pair;
    for (const vri::FlipResult& same :
         {vri::ldrFlip(pair.reference, pair.reference), vri::hdrFlip(pair.reference, pair.reference)}) {
        CHECK(std::all_of(same.errorMap.begin(), same.errorMap.end(), [](float e) { return e == 0.0f; }));
        CHECK(same.mean == 0.0);
        CHECK(same.max == 0.0);
    }
    const vri::Image hdrTest = rgbImage(40, 30, [&](int x, int y) {
        return std::array<float, 3>{pair.test.at(x, y, 0) * 40.0f, pair.test.at(x, y, 1),
                                    pair.test.at(x, y, 2) * 0.01f};
    });
    for (const vri::FlipResult& flip :
         {vri::ldrFlip(pair.reference, pair.test), vri::hdrFlip(pair.reference, hdrTest)}) {
        CHECK(flip.errorMap.size() == 40u * 30u);
        CHECK(std::all_of(flip.errorMap.begin(), flip.errorMap.end(), [](float e) { return e >= 0.0f && e <= 1.0f; }));
        CHECK(flip.mean > 0.0);
        CHECK(flip.max <= 1.0);
        CHECK(flip.median <= flip.p95);
        CHECK(flip.p95 <= flip.max);
    }
    // The fireflies stand out: the largest error is at one of them.
    const vri::FlipResult flip = vri::ldrFlip(pair.reference, pair.test);
    const auto worst = std::max_element(flip.errorMap.begin(), flip.errorMap.end()) - flip.errorMap.begin();
    CHECK(((worst == 4 * 40 + 5) || (worst == 13 * 40 + 16) || (worst == 22 * 40 + 27)));
}

TEST_CASE("FLIP: a mask chooses the pixels the statistics count, not the error map") {
    const SmallPair pair;
    const vri::FlipResult all = vri::ldrFlip(pair.reference, pair.test);
    vri::PixelMask left = vri::fullMask(40, 30);
    for (int y = 0; y < 30; ++y)
        for (int x = 20; x < 40; ++x) left.keep[static_cast<std::size_t>(y) * 40 + x] = 0;
    left.count = 20 * 30;
    const vri::FlipResult masked = vri::ldrFlip(pair.reference, pair.test, {}, &left);
    CHECK(masked.errorMap == all.errorMap);
    CHECK(masked.pixels == 600);
    CHECK(masked.mean == doctest::Approx(meanOver(all.errorMap, left)).epsilon(1e-12));
    // The tint is on the right: the left half's mean is below the whole image's.
    CHECK(masked.mean < all.mean);
    const vri::PixelMask full = vri::fullMask(40, 30);
    CHECK(vri::ldrFlip(pair.reference, pair.test, {}, &full).mean == all.mean);

    vri::PixelMask none = vri::fullMask(40, 30);
    std::fill(none.keep.begin(), none.keep.end(), 0);
    none.count = 0;
    const vri::FlipResult empty = vri::ldrFlip(pair.reference, pair.test, {}, &none);
    CHECK(empty.pixels == 0);
    CHECK(empty.mean == 0.0);
    CHECK(empty.errorMap == all.errorMap);
}

TEST_CASE("FLIP: channels are found by name, alpha ignored; LDR-FLIP clamps to [0, 1]") {
    const SmallPair pair;
    const vri::FlipResult rgb = vri::ldrFlip(pair.reference, pair.test);
    // BGRA with a random alpha: the same errors.
    const auto bgra = [](const vri::Image& image) {
        vri::Image out(image.width, image.height, 4);
        out.channelNames = {"B", "G", "R", "A"};
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                for (int k = 0; k < 3; ++k) out.at(x, y, 2 - k) = image.at(x, y, k);
                out.at(x, y, 3) = static_cast<float>((x * 7 + y * 3) % 5) / 4.0f;
            }
        return out;
    };
    CHECK(vri::ldrFlip(bgra(pair.reference), bgra(pair.test)).errorMap == rgb.errorMap);
    // Values above 1 and below 0 are the display's 1 and 0.
    vri::Image brighter = pair.test, darker = pair.test;
    for (std::size_t i = 0; i < brighter.pixels.size(); ++i) {
        if (pair.test.pixels[i] == 1.0f) brighter.pixels[i] = 7.0f;
        if (pair.test.pixels[i] < 0.05f) darker.pixels[i] = -3.0f;
    }
    vri::Image clampedDarker = darker;
    for (float& v : clampedDarker.pixels) v = std::max(v, 0.0f);
    CHECK(vri::ldrFlip(pair.reference, brighter).errorMap == rgb.errorMap);
    CHECK(vri::ldrFlip(pair.reference, darker).errorMap == vri::ldrFlip(pair.reference, clampedDarker).errorMap);
}

TEST_CASE("FLIP: HDR-FLIP takes the exposures given and computes the others") {
    const SmallPair pair;
    vri::FlipHdrOptions options;
    options.startExposure = -1.0;
    options.stopExposure = 2.5;
    const vri::FlipResult given = vri::hdrFlip(pair.reference, pair.test, {}, nullptr, options);
    CHECK(given.exposures.start == -1.0);
    CHECK(given.exposures.stop == 2.5);
    CHECK(given.exposures.count == 4);  // ceil(2.5 - -1)
    // Exposures -1 and 2 are among -1, 0, 1, 2: the worst errors over them are at most those over all four.
    options.stopExposure = 2.0;
    options.exposures = 2;
    const vri::FlipResult two = vri::hdrFlip(pair.reference, pair.test, {}, nullptr, options);
    options.exposures = 4;
    const vri::FlipResult four = vri::hdrFlip(pair.reference, pair.test, {}, nullptr, options);
    CHECK(two.exposures.count == 2);
    CHECK(std::equal(two.errorMap.begin(), two.errorMap.end(), four.errorMap.begin(), std::less_equal<float>()));
    CHECK(two.mean <= four.mean);

    vri::FlipHdrOptions onlyStart;
    onlyStart.startExposure = 0.5;
    const vri::FlipResult half = vri::hdrFlip(pair.reference, pair.test, {}, nullptr, onlyStart);
    CHECK(half.exposures.start == 0.5);
    CHECK(half.exposures.stop == vri::flipExposureRange(pair.reference).stop);
}

TEST_CASE("FLIP: the exposure range of a render over black comes from a mask") {
    // A bright square over a black background that covers most of the image: the median pixel is black.
    const vri::Image render = rgbImage(20, 20, [](int x, int y) {
        const bool inside = x >= 5 && x < 12 && y >= 5 && y < 12;
        return std::array<float, 3>{inside ? 4.0f : 0.0f, inside ? 2.0f + x / 10.0f : 0.0f, inside ? 1.0f : 0.0f};
    });
    CHECK_THROWS_WITH_AS(vri::flipExposureRange(render),
                         doctest::Contains("the reference's median luminance is 0.000000"), vri::Error);
    CHECK_THROWS_AS(vri::hdrFlip(render, render), vri::Error);
    vri::PixelMask square = vri::fullMask(20, 20);
    square.count = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * 20 + x;
            square.keep[p] = render.at(x, y, 0) > 0.0f;
            square.count += square.keep[p];
        }
    const vri::FlipExposureRange range = vri::flipExposureRange(render, vri::FlipToneMapper::Aces, &square);
    CHECK(range.start < range.stop);
    CHECK(range.count >= 2);
    vri::FlipHdrOptions options;
    options.startExposure = range.start;
    options.stopExposure = range.stop;
    CHECK(vri::hdrFlip(render, render, {}, &square, options).max == 0.0);
}

TEST_CASE("FLIP: inputs it cannot compare are errors that say why") {
    const SmallPair pair;
    CHECK_THROWS_WITH_AS(vri::ldrFlip(pair.reference, vri::Image(40, 31, 3)),
                         "LDR-FLIP: the images differ in size: 40x30 vs 40x31", vri::Error);
    vri::Image noBlue = pair.test;
    noBlue.channelNames = {"R", "G", "Y"};
    CHECK_THROWS_WITH_AS(vri::ldrFlip(pair.reference, noBlue),
                         "LDR-FLIP: the test image has no channel 'B' (it has R,G,Y)", vri::Error);
    vri::Image broken = pair.test;
    broken.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH_AS(vri::hdrFlip(broken, pair.test), "HDR-FLIP: the reference's channel G is nan at pixel 3,2",
                         vri::Error);
    const vri::PixelMask wrong = vri::fullMask(30, 30);
    CHECK_THROWS_WITH_AS(vri::ldrFlip(pair.reference, pair.test, {}, &wrong),
                         "LDR-FLIP: the mask has 900 pixels, the images 1200", vri::Error);
    CHECK_THROWS_AS(vri::ldrFlip(pair.reference, pair.test, vri::FlipViewing{0.0, 0.7, 3840}), vri::Error);
    CHECK_THROWS_AS(vri::ldrFlip(pair.reference, pair.test, vri::FlipViewing{0.7, 0.7, 1e9}), vri::Error);

    vri::FlipHdrOptions reversed;
    reversed.startExposure = 3.0;
    reversed.stopExposure = 1.0;
    CHECK_THROWS_WITH_AS(vri::hdrFlip(pair.reference, pair.test, {}, nullptr, reversed),
                         "HDR-FLIP: the start exposure 3.000000 is above the stop exposure 1.000000", vri::Error);
    vri::FlipHdrOptions one;
    one.exposures = 1;
    CHECK_THROWS_WITH_AS(vri::hdrFlip(pair.reference, pair.test, {}, nullptr, one),
                         "HDR-FLIP: the number of exposures must be at least 2, got 1", vri::Error);
    vri::FlipHdrOptions far;
    far.startExposure = -200.0;
    CHECK_THROWS_AS(vri::hdrFlip(pair.reference, pair.test, {}, nullptr, far), vri::Error);
}
