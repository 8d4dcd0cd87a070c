#include <doctest/doctest.h>

#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "libvri/render/exact_reference_json.h"
#include "libvri/render/render_job.h"
#include "libvri/render/render_json.h"
#include "libvri/render/stats_schema.h"
#include "libvri/util/error.h"

using namespace vri;
using nlohmann::json;

namespace {

// The dotted paths of a record's leaves, arrays counted as leaves: "stats.error_bound.max".
void leaves(const json& node, const std::string& path, std::set<std::string>& out) {
    if (node.is_object() && !node.empty()) {
        for (const auto& [key, value] : node.items()) leaves(value, path.empty() ? key : path + "." + key, out);
        return;
    }
    out.insert(path);
}

// A render's stats with every optional part present, as the writers see them.
json everyWrittenField() {
    RenderStats render;
    render.seconds = 2;
    render.device = "lavapipe";
    render.interpolation = "shader";
    render.voxelLoads = "gather";
    render.adaptive = AdaptiveCounts{};
    render.simpsonRange = SimpsonRange{};
    render.preintegration = RenderStats::Preintegration{};  // order 2 on the CPU: every field
    render.preintegration->order = 2;
    render.preintegration->error.deltas = {0.0, 0.25};
    render.preintegration->error.colourByDelta = render.preintegration->error.alphaByDelta = {0.0, 0.0};
    render.preintegration->largestDelta = 0.1;
    render.preintegration->lookupsByDelta = {1, 2, 0};
    render.nonfinite.count = 1;
    json record = {{"stats", toJson(render)}, {"timing", frameTimingRecord(1, {1.0, 2.0})}};
    putOutOfRange(record, OutOfRangePixels{});
    const json exact = toJson(ExactReferenceStats{});
    for (const auto& [key, value] : exact.items()) record["stats"][key] = value;
    return record;
}

}  // namespace

TEST_CASE("stats schema: every field the writers write is declared, and every declared stats field is written") {
    std::set<std::string> written;
    leaves(everyWrittenField(), "", written);
    for (const std::string& path : written) {
        INFO(path);
        CHECK(statsFieldOf(path) != nullptr);
    }
    // Fields only the outside renderer's record or the experiment runner sets, or wholes written as objects.
    const std::set<std::string> elsewhere = {"stats.max_error_search", "stats.quantisation", "timing.timed", "machine"};
    for (const StatsField& field : statsSchema()) {
        const std::string name = field.dotted();
        if (elsewhere.contains(name)) continue;
        INFO(name);
        CHECK(std::ranges::any_of(written, [&](const std::string& w) { return w == name || w.starts_with(name + "."); }));
    }
}

TEST_CASE("stats schema: names are unique and sit in stats, timing or machine") {
    std::set<std::string> seen;
    for (const StatsField& field : statsSchema()) {
        INFO(field.pointer);
        CHECK(seen.insert(std::string(field.pointer)).second);
        CHECK((field.pointer.starts_with("/stats/") || field.pointer.starts_with("/timing/") || field.pointer == "/machine"));
    }
    CHECK(stats_field::errorBoundMax.dotted() == "stats.error_bound.max");
}

TEST_CASE("stats schema: a value path into stats is checked against it") {
    REQUIRE(statsFieldOf("stats.error_bound.max.2"));
    CHECK(statsFieldOf("stats.error_bound.max.2")->pointer == stats_field::errorBoundMax.pointer);
    REQUIRE(statsFieldOf("timing.load.overloaded"));
    CHECK(statsFieldOf("timing.load.overloaded")->pointer == stats_field::load.pointer);
    CHECK(statsFieldOf("stats.error_bound") == nullptr);  // an object of several fields, not one
    CHECK_NOTHROW(requireStatsField("timing.median_wall_seconds", "value"));
    CHECK_NOTHROW(requireStatsField("channels.3.max_abs", "value"));  // a vri-diff record's
    CHECK_THROWS_WITH_AS(requireStatsField("stats.wal_seconds", "tables.t: value"),
                         "tables.t: value: 'stats.wal_seconds' is no field of a render's stats (nearest: "
                         "stats.wall_seconds); docs/stats.md lists them",
                         Error);
}

TEST_CASE("stats schema: docs/stats.md lists every field with its tile rule") {
    std::ifstream in(std::string(VRI_TEST_DATA_DIR) + "/../../docs/stats.md");
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    for (const StatsField& field : statsSchema()) {
        INFO(field.dotted());
        CHECK(text.str().find("| `" + field.dotted() + "` |") != std::string::npos);
    }
}
