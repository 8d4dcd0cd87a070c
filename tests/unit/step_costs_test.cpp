// Pricing an experiment's steps from its last manifest: same id and arguments, priced at the recorded wall
// time; a new step, or one whose arguments changed, unpriced; no manifest, nothing priced.
#include <doctest/doctest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "temp_dir.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/util/error.h"

namespace {

vri::Step step(const std::string& id, const std::string& kind, std::vector<std::string> arguments) {
    return vri::Step{id, kind, "vri-x", std::move(arguments), {}, {}, {}};
}

}  // namespace

TEST_CASE("estimateCost prices the steps a manifest ran with the same arguments") {
    vri::test::TempDir dir{"step-costs"};
    vri::Plan plan{dir.path, dir.path, {}, {}};
    plan.steps = {step("a", "render", {"--size", "8x6", "-o", "a.exr"}), step("b", "diff", {"a.exr", "b.exr"}),
                  step("c", "render", {"--size", "4x3", "-o", "c.exr"}), step("d", "table", {"-o", "d.md"})};
    const nlohmann::json manifest = {
        {"steps",
         {{{"id", "a"}, {"command", "build/bin/vri-x --size 8x6 -o a.exr"}, {"wall_seconds", 2.5}},
          {{"id", "b"}, {"command", "/elsewhere/bin/vri-x a.exr b.exr"}, {"wall_seconds", 0.25}},
          {{"id", "c"}, {"command", "build/bin/vri-x --size 8x6 -o c.exr"}, {"wall_seconds", 9.0}},  // resized since
          {{"id", "gone"}, {"command", "build/bin/vri-x"}, {"wall_seconds", 100.0}}}}};
    std::ofstream(dir / "manifest.json") << manifest.dump();

    const vri::CostEstimate e = vri::estimateCost(plan, dir / "manifest.json");
    CHECK(e.hasManifest);
    CHECK(e.priced == 2);
    CHECK(e.unpriced == 2);  // c changed, d is new
    CHECK(e.seconds == doctest::Approx(2.75));
    CHECK(e.byKind.at("render") == doctest::Approx(2.5));
    CHECK(e.byKind.at("diff") == doctest::Approx(0.25));
    CHECK_FALSE(e.byKind.contains("table"));
    CHECK(vri::manifestSeconds(manifest) == doctest::Approx(111.75));

    const vri::CostEstimate none = vri::estimateCost(plan, dir / "absent.json");
    CHECK_FALSE(none.hasManifest);
    CHECK(none.priced == 0);
    CHECK(none.unpriced == 4);
    CHECK(none.seconds == 0);
}

TEST_CASE("estimateCost refuses a manifest that is not one, naming it") {
    vri::test::TempDir dir{"step-costs-bad"};
    vri::Plan plan{dir.path, dir.path, {step("a", "render", {"-o", "a.exr"})}, {{}}};
    std::ofstream(dir / "manifest.json") << R"({"steps": [{"id": "a"}]})";
    CHECK_THROWS_WITH_AS(vri::estimateCost(plan, dir / "manifest.json"), doctest::Contains("manifest.json"),
                         vri::Error);
}

TEST_CASE("stepPrices leaves unpriced a step whose recorded time no step can take (issue 48, class 7)") {
    vri::test::TempDir dir{"step-costs-forged"};
    vri::Plan plan{dir.path, dir.path, {}, {}};
    plan.steps = {step("a", "render", {"-o", "a.exr"}), step("b", "render", {"-o", "b.exr"}),
                  step("c", "render", {"-o", "c.exr"}), step("d", "render", {"-o", "d.exr"})};
    const nlohmann::json manifest = {
        {"steps",
         {{{"id", "a"}, {"command", "vri-x -o a.exr"}, {"wall_seconds", 1e300}},
          {{"id", "b"}, {"command", "vri-x -o b.exr"}, {"wall_seconds", -1e6}},
          {{"id", "c"}, {"command", "vri-x -o c.exr"}, {"wall_seconds", 31.0 * 24 * 3600}},
          {{"id", "d"}, {"command", "vri-x -o d.exr"}, {"wall_seconds", 4.5}}}}};
    std::ofstream(dir / "manifest.json") << manifest.dump();
    const std::vector<std::optional<double>> prices = vri::stepPrices(plan, dir / "manifest.json");
    CHECK_FALSE(prices[0]);
    CHECK_FALSE(prices[1]);
    CHECK_FALSE(prices[2]);
    REQUIRE(prices[3]);
    CHECK(*prices[3] == 4.5);
}

TEST_CASE("secondsText switches to minutes from two minutes on") {
    CHECK(vri::secondsText(42.06) == "42.1 s");
    CHECK(vri::secondsText(119.9) == "119.9 s");
    CHECK(vri::secondsText(2844) == "47.4 min");
}
