#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "libvri/render/tile_merge.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/util/error.h"
#include "libvri/util/parse.h"

using namespace vri;
using nlohmann::json;

namespace {

// A tile's stats file as vri-render writes it, with the fields the rules read.
json renderTile(std::uint64_t rays, double seconds, std::vector<double> frames, double leftOut) {
    return {{"machine", {{"host", "a"}}},
            {"stats",
             {{"rays", rays},
              {"rays_hit", rays / 2},
              {"samples_evaluated", 1000 * rays},
              {"samples_per_second", 1.0},
              {"wall_seconds", seconds},
              {"setup_seconds", 0.5},
              {"setup_reused", false},
              {"threads", 2},
              {"backend", "cpu"},
              {"simd_target", "AVX2"},
              {"termination_left_out_max", leftOut},
              {"adaptive", {{"inner_tries", rays}, {"outer_steps", 2 * rays}}},
              {"nonfinite_pixels", 0},
              {"out_of_range_pixels", {{"pixels", 1}, {"channels_above_1", 2}, {"channels_below_0", 0}, {"max", 1.5}, {"min", 0.0}}},
              {"error_bound", {{"channels", {"R", "G", "B", "A"}}, {"max", {1e-8, 2e-8, 0, 0}}, {"mean", {1e-9, 0, 0, 0}}}}}},
            {"timing", {{"warm_up_frames", 0}, {"repeats", frames.size()}, {"wall_seconds", frames}, {"median_wall_seconds", 0}}}};
}

}  // namespace

TEST_CASE("tile stats: counts and seconds add, maxima and minima stay, means weigh by pixels") {
    json a = renderTile(100, 1.0, {1.0, 3.0, 2.0}, 1e-5);
    json b = renderTile(300, 2.0, {2.0, 2.0, 5.0}, 3e-5);
    b["stats"]["error_bound"]["max"] = {3e-8, 1e-8, 0, 1e-9};
    b["stats"]["error_bound"]["mean"] = {3e-9, 0, 0, 0};
    b["stats"]["out_of_range_pixels"]["min"] = -0.25;
    b["stats"]["first_nonfinite_pixel"] = {7, 40};
    b["stats"]["nonfinite_pixels"] = 2;
    b["stats"]["threads"] = 16;           // another machine: not the whole image's
    b["machine"] = {{"host", "b"}};
    b["stats"]["something_new"] = 1;      // no rule: not combined
    const json m = combineTileStats({a, b}, {"a.json", "b.json"});
    const json& s = m["stats"];
    CHECK(s["rays"] == 400);
    CHECK(s["rays_hit"] == 200);
    CHECK(s["samples_evaluated"] == 400000);
    CHECK(s["wall_seconds"] == 3.0);
    CHECK(s["samples_per_second"] == doctest::Approx(400000 / 3.0));
    CHECK(s["setup_seconds"] == 1.0);
    CHECK(s["setup_reused"] == false);
    CHECK(s["backend"] == "cpu");
    CHECK(s["simd_target"] == "AVX2");
    CHECK(s["termination_left_out_max"] == 3e-5);
    CHECK(s["adaptive"]["inner_tries"] == 400);
    CHECK(s["adaptive"]["outer_steps"] == 800);
    CHECK(s["nonfinite_pixels"] == 2);
    CHECK(s["first_nonfinite_pixel"] == json({7, 40}));
    CHECK(s["out_of_range_pixels"]["pixels"] == 2);
    CHECK(s["out_of_range_pixels"]["channels_above_1"] == 4);
    CHECK(s["out_of_range_pixels"]["max"] == 1.5);
    CHECK(s["out_of_range_pixels"]["min"] == -0.25);
    CHECK(s["error_bound"]["channels"] == json({"R", "G", "B", "A"}));
    CHECK(s["error_bound"]["max"] == json({3e-8, 2e-8, 0.0, 1e-9}));
    CHECK(s["error_bound"]["mean"][0].get<double>() == doctest::Approx((100 * 1e-9 + 300 * 3e-9) / 400));
    // Frame k of the whole is frame k of each tile, one after the other; the median is the sums'.
    CHECK(m["timing"]["wall_seconds"] == json({3.0, 5.0, 7.0}));
    CHECK(m["timing"]["median_wall_seconds"] == 5.0);
    CHECK(m["timing"]["repeats"] == 3);
    // What differs between the tiles, or has no rule, is null and named.
    CHECK(s["threads"].is_null());
    CHECK(s["something_new"].is_null());
    CHECK(m["machine"].is_null());
    CHECK(m["not_combined"] == json({"stats.threads", "stats.something_new", "machine"}));
}

TEST_CASE("tile stats: the first non-finite pixel is the first in row order of any tile") {
    json a = renderTile(10, 1.0, {1.0}, 0), b = renderTile(10, 1.0, {1.0}, 0), c = renderTile(10, 1.0, {1.0}, 0);
    a["stats"]["first_nonfinite_pixel"] = {5, 9};
    c["stats"]["first_nonfinite_pixel"] = {2, 9};
    const json m = combineTileStats({a, b, c}, {"a", "b", "c"});
    CHECK(m["stats"]["first_nonfinite_pixel"] == json({2, 9}));
    CHECK(m["not_combined"].empty());
    CHECK_FALSE(combineTileStats({b, b}, {"a", "b"})["stats"].contains("first_nonfinite_pixel"));
}

TEST_CASE("tile stats: a derived field whose sources are not combined is null and listed, not made up") {
    json a = renderTile(10, 1.0, {1.0}, 0), b = renderTile(10, 1.0, {1.0}, 0);
    b["stats"]["samples_evaluated"] = "many";  // edited by hand: the sum has no number, nor has the rate
    b["timing"]["wall_seconds"] = {"x"};
    const json m = combineTileStats({a, b}, {"a", "b"});
    CHECK(m["stats"]["samples_per_second"].is_null());
    CHECK(m["timing"]["median_wall_seconds"].is_null());
    const json& listed = m["not_combined"];
    for (const char* name : {"stats.samples_evaluated", "stats.samples_per_second", "timing.wall_seconds",
                             "timing.median_wall_seconds"}) {
        INFO(name);
        CHECK(std::ranges::find(listed, json(name)) != listed.end());
    }
}

TEST_CASE("tile stats: tiles timed with different frame counts are refused") {
    const json a = renderTile(10, 1.0, {1.0}, 0), b = renderTile(10, 1.0, {1.0, 2.0}, 0);
    CHECK_THROWS_WITH_AS(combineTileStats({a, b}, {"a.json", "b.json"}),
                         "b.json: timing.repeats is 2, but a.json has 1 (the tiles of one image must agree in it)", Error);
    json c = renderTile(10, 1.0, {1.0}, 0);
    c["stats"]["error_bound"]["max"] = {1.0, 2.0};
    CHECK_THROWS_WITH_AS(combineTileStats({a, c}, {"a.json", "c.json"}),
                         "c.json: stats.error_bound.max has 2 elements, but a.json has 4", Error);
}

TEST_CASE("row bands: balanced bands of whole rows that cover the image once") {
    const std::vector<PixelRegion> bands = rowBands(7, 10, 4);
    REQUIRE(bands.size() == 4);
    CHECK(bands[0] == PixelRegion{0, 0, 7, 2});
    CHECK(bands[1] == PixelRegion{0, 2, 7, 3});
    CHECK(bands[2] == PixelRegion{0, 5, 7, 2});
    CHECK(bands[3] == PixelRegion{0, 7, 7, 3});
    CHECK(rowBands(3, 5, 5).back() == PixelRegion{0, 4, 3, 1});
    CHECK(rowBands(3, 5, 1).front() == PixelRegion::whole(3, 5));
}

TEST_CASE("--region: four integers inside int, or a usage error") {
    CHECK(parseRegion("0,2,5,7", "--region") == glm::ivec4(0, 2, 5, 7));
    for (const char* bad : {"1,2,3", "1,2,3,4,5", "a,0,1,1", "-1,0,1,1", "0,0,0,1", "0,0,1,-2", "2147483647,0,1,1",
                            "0,2147483000,1,1000", "0,0,99999999999,1", "1.5,0,1,1", ""})
        CHECK_THROWS_WITH_AS(parseRegion(bad, "--region"), doctest::Contains("--region: expected a pixel rectangle"),
                             UsageError);
    CHECK(PixelRegion{0, 0, 4, 4}.inside(4, 4));
    CHECK_FALSE(PixelRegion{1, 0, 4, 4}.inside(4, 4));
    CHECK_FALSE(PixelRegion{2147483000, 0, 1000, 1}.inside(4, 4));
}
