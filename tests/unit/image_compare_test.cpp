#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "libvri/render/image_compare_json.h"
#include "libvri/core/image_compare.h"
#include "libvri/util/error.h"

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A 4x1 pair whose R errors are 0, 0.002, 0.006, 0.02 and whose other channels agree.
struct KnownPair {
    vri::Image a{4, 1}, b{4, 1};
    KnownPair() {
        const float r[] = {0.0f, 0.002f, 0.006f, 0.02f};
        for (int x = 0; x < 4; ++x) {
            b.at(x, 0, 0) = r[x];
            for (int c = 1; c < 4; ++c) a.at(x, 0, c) = b.at(x, 0, c) = 0.25f * c;
        }
    }
};

}  // namespace

TEST_CASE("image compare: per-channel statistics of a hand-made pair") {
    KnownPair pair;
    const vri::ImageDiff diff = vri::compareImages(pair.a, pair.b, {0.01, 0.005, 0.001});
    CHECK(diff.width == 4);
    CHECK(diff.height == 1);
    CHECK(diff.pixels == 4);
    REQUIRE(diff.channels.size() == 4);

    const vri::ChannelDiff& r = diff.channels[0];
    CHECK(r.name == "R");
    CHECK(r.countAbove == std::vector<std::uint64_t>{1, 2, 3});
    CHECK(r.percentAbove == std::vector<double>{25.0, 50.0, 75.0});
    CHECK(r.maxAbs == static_cast<double>(0.02f));
    CHECK(r.maxX == 3);
    CHECK(r.maxY == 0);
    // By hand: mean = (0.002 + 0.006 + 0.02) / 4 = 0.007, RMSE = sqrt((4e-6 + 3.6e-5 + 4e-4) / 4) = sqrt(1.1e-4).
    CHECK(r.meanAbs == doctest::Approx(0.007).epsilon(1e-6));
    CHECK(r.rmse == doctest::Approx(std::sqrt(1.1e-4)).epsilon(1e-6));

    for (int c = 1; c < 4; ++c) {
        CHECK(diff.channels[c].maxAbs == 0.0);
        CHECK(diff.channels[c].rmse == 0.0);
        CHECK(diff.channels[c].countAbove == std::vector<std::uint64_t>{0, 0, 0});
    }
}

TEST_CASE("image compare: an error equal to a threshold is not above it") {
    vri::Image a(2, 1, 1), b(2, 1, 1);
    a.pixels = {0.5f, 0.75f};
    b.pixels = {0.25f, 1.0f};  // errors exactly 0.25 (dyadic: no rounding anywhere)
    const vri::ImageDiff diff = vri::compareImages(a, b, {0.25, 0.125});
    CHECK(diff.channels[0].countAbove == std::vector<std::uint64_t>{0, 2});
    CHECK(diff.channels[0].maxAbs == 0.25);
}

TEST_CASE("image compare: NaN against a number is an infinite error, equal NaNs and infinities agree") {
    vri::Image a(4, 1, 1), b(4, 1, 1);
    a.pixels = {std::nanf(""), std::nanf(""), kInfinity, -kInfinity};
    b.pixels = {1.0f, std::nanf(""), kInfinity, kInfinity};
    const vri::ImageDiff diff = vri::compareImages(a, b, {1e30});
    CHECK(diff.channels[0].countAbove == std::vector<std::uint64_t>{2});
    CHECK(std::isinf(diff.channels[0].maxAbs));
    CHECK(diff.channels[0].maxX == 0);
    const vri::Image difference = vri::differenceImage(a, b);
    CHECK(std::isinf(difference.pixels[0]));
    CHECK(difference.pixels[1] == 0.0f);
    CHECK(difference.pixels[2] == 0.0f);
    CHECK(std::isinf(difference.pixels[3]));
    vri::Image c(2, 1, 1), d(2, 1, 1);
    c.pixels = {0.25f, 1.0f};
    d.pixels = {0.5f, 1.0f};
    CHECK(vri::differenceImage(c, d, 4.0).pixels == std::vector<float>{1.0f, 0.0f});  // scaled for a picture
}

TEST_CASE("image compare: different shapes throw and name both") {
    const vri::Image a(4, 1), b(2, 2), c(4, 1, 3);
    CHECK_THROWS_WITH_AS(vri::compareImages(a, b, {0.01}), "images differ in shape: 4x1 with 4 channels vs 2x2 with 4 channels",
                         vri::Error);
    CHECK_THROWS_WITH_AS(vri::compareImages(a, c, {0.01}), doctest::Contains("vs 4x1 with 3 channels"), vri::Error);
    CHECK_THROWS_AS(vri::differenceImage(a, b), vri::Error);
    CHECK_THROWS_AS(vri::errorHistogram(a, c, {0.1}), vri::Error);
}

TEST_CASE("image compare: difference image is |a - b| per channel, names from a") {
    KnownPair pair;
    pair.a.channelNames = {"R", "G", "B", "alpha"};
    const vri::Image difference = vri::differenceImage(pair.a, pair.b);
    CHECK(difference.channelNames == pair.a.channelNames);
    CHECK(vri::differenceImage(pair.b, pair.a).channelNames[3] == "A");
    CHECK(difference.at(3, 0, 0) == 0.02f);
    CHECK(difference.at(3, 0, 1) == 0.0f);
}

TEST_CASE("image compare: histogram bins, zero and overflow bins, counts sum to the pixels") {
    KnownPair pair;
    pair.b.at(0, 0, 1) = 5.0f;  // G error 4.75: overflow
    const vri::ErrorHistogram histogram = vri::errorHistogram(pair.a, pair.b, {0.001, 0.01});
    REQUIRE(histogram.binCount() == 4);
    CHECK(histogram.binLower(0) == 0.0);
    CHECK(histogram.binUpper(0) == 0.0);
    CHECK(histogram.binUpper(1) == 0.001);
    CHECK(histogram.binLower(3) == 0.01);
    CHECK(std::isinf(histogram.binUpper(3)));
    // R errors 0, 0.002, 0.006, 0.02: zero, (0.001, 0.01] twice, above 0.01.
    CHECK(histogram.counts[0] == std::vector<std::uint64_t>{1, 0, 2, 1});
    CHECK(histogram.counts[1] == std::vector<std::uint64_t>{3, 0, 0, 1});
    CHECK(histogram.counts[2] == std::vector<std::uint64_t>{4, 0, 0, 0});
    for (const auto& counts : histogram.counts)
        CHECK(std::accumulate(counts.begin(), counts.end(), std::uint64_t{0}) == histogram.pixels);

    CHECK(vri::toCsv(histogram) ==
          "bin_lo,bin_hi,R,G,B,A\n"
          "0,0,1,3,4,4\n"
          "0,0.001,0,0,0,0\n"
          "0.001,0.01,2,0,0,0\n"
          "0.01,inf,1,1,0,0\n");
}

TEST_CASE("image compare: histogram agrees with the counts above each edge") {
    vri::Image a(17, 13), b(17, 13);
    std::uint32_t state = 12345;  // a fixed pseudo-random sequence, spread over six decades
    for (std::size_t i = 0; i < b.pixels.size(); ++i) {
        state = state * 1664525u + 1013904223u;
        b.pixels[i] = (state % 7 == 0) ? 0.0f : std::pow(10.0f, -6.0f + 6.0f * (state >> 8) / float(1 << 24));
    }
    const std::vector<double> edges = vri::logBinEdges(1e-6, 1.0, 3);
    const vri::ErrorHistogram histogram = vri::errorHistogram(a, b, edges);
    const vri::ImageDiff diff = vri::compareImages(a, b, edges);
    for (std::size_t c = 0; c < 4; ++c) {
        const auto& counts = histogram.counts[c];
        CHECK(std::accumulate(counts.begin(), counts.end(), std::uint64_t{0}) == histogram.pixels);
        for (std::size_t e = 0; e < edges.size(); ++e)  // bins past edge e start at index e + 2
            CHECK(std::accumulate(counts.begin() + e + 2, counts.end(), std::uint64_t{0}) == diff.channels[c].countAbove[e]);
    }
}

TEST_CASE("image compare: logarithmic bin edges") {
    const std::vector<double> edges = vri::logBinEdges(1e-3, 1.0, 2);
    REQUIRE(edges.size() == 7);
    CHECK(edges.front() == 1e-3);
    CHECK(edges[1] == doctest::Approx(std::sqrt(10.0) * 1e-3));
    CHECK(edges[2] == doctest::Approx(1e-2));
    CHECK(edges[4] == doctest::Approx(0.1));
    CHECK(edges.back() == 1.0);
    CHECK(vri::logBinEdges(1e-3, 0.5, 1) == std::vector<double>{1e-3, edges[2], edges[4], 0.5});
    CHECK_THROWS_AS(vri::logBinEdges(0.0, 1.0, 4), vri::Error);
    CHECK_THROWS_AS(vri::logBinEdges(1.0, 0.1, 4), vri::Error);
    CHECK_THROWS_AS(vri::logBinEdges(1e-3, 1.0, 0), vri::Error);
    const vri::Image a(1, 1);
    CHECK_THROWS_AS(vri::errorHistogram(a, a, {}), vri::Error);
    CHECK_THROWS_AS(vri::errorHistogram(a, a, {0.1, 0.1}), vri::Error);
}

TEST_CASE("image compare: JSON carries every statistic and says all pixels count") {
    KnownPair pair;
    const nlohmann::json json = vri::toJson(vri::compareImages(pair.a, pair.b, {0.01, 0.005, 0.001}));
    CHECK(json["pixels_counted"] == "all");
    CHECK(json["pixels"] == 4);
    CHECK(json["thresholds"] == nlohmann::json{0.01, 0.005, 0.001});
    const nlohmann::json& r = json["channels"][0];
    CHECK(r["name"] == "R");
    CHECK(r["max_at"] == nlohmann::json{3, 0});
    CHECK(r["above"][2]["threshold"] == 0.001);
    CHECK(r["above"][2]["count"] == 3);
    CHECK(r["above"][2]["percent"] == 75.0);
    CHECK(r.contains("mean_abs"));
    CHECK(r.contains("rmse"));
}
