#include <doctest/doctest.h>

#include <set>
#include <string>

#include "libvri/core/render_option_table.h"
#include "libvri/util/error.h"

namespace {

vri::RenderRequest given(vri::RenderTool tool, std::initializer_list<std::pair<std::string, std::string>> values) {
    vri::RenderRequest request(tool);
    for (const auto& [flag, text] : values)
        for (const vri::RenderOptionRow& row : vri::renderOptionTable())
            if (row.flag() == flag) {
                row.apply(text, flag, request);
                request.given.push_back(row.flag());
            }
    vri::finishRenderRequest(request);
    return request;
}

std::set<std::string> names(const std::vector<vri::Setting>& settings) {
    std::set<std::string> result;
    for (const vri::Setting& s : settings) result.emplace(s.name);
    return result;
}

}  // namespace

TEST_CASE("render option table: each flag and experiment key is declared once") {
    std::set<std::string> flags, keys;
    for (const vri::RenderOptionRow& row : vri::renderOptionTable()) {
        CHECK(flags.emplace(row.flag()).second);
        if (!row.key.empty()) CHECK(keys.emplace(row.key).second);
        CHECK((row.apply && row.shownDefault && row.record));
        CHECK(row.tools != 0);
        CHECK(row.backends != 0);
    }
    CHECK(vri::findRenderOption("eps")->flag() == "--tolerance");
    CHECK(vri::findRenderOption("tile_size") == nullptr);
}

TEST_CASE("render option table: values land in the request as the tools had them") {
    const vri::RenderRequest step = given(vri::RenderTool::Render, {{"--step", "0.25"}});
    CHECK(step.options.samplingRate == 1.0 / 0.25);
    CHECK(vri::RenderRequest(vri::RenderTool::Render).options.samplingRate == 2.0);
    CHECK(vri::RenderRequest(vri::RenderTool::Reference).options.samplingRate == 1.0 / 0.01);
    CHECK(vri::RenderRequest(vri::RenderTool::Reference).exact);
    const vri::RenderRequest vulkan = given(vri::RenderTool::Render, {{"--backend", "vulkan"}});
    CHECK(vulkan.options.precision == vri::Precision::Float);  // Vulkan's default precision
    const vri::RenderRequest exact = given(vri::RenderTool::Render, {{"--method", "exact"}});
    CHECK(exact.exactOptions().tolerance == 1e-7);  // vri-render's exact default
    CHECK(given(vri::RenderTool::Render, {{"--method", "exact"}, {"--tolerance", "1e-9"}}).exactOptions().tolerance == 1e-9);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Render, {{"--step", "0"}}), "--step: expected a number > 0, got '0'",
                         vri::Error);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Render, {{"--method", "exact"}, {"--rate", "2"}}),
                         "--step, --rate: --method exact has no step", vri::Error);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Reference, {{"--method", "simpson"}}),
                         "--method: unknown method 'simpson' (expected exact or riemann)", vri::Error);
}

TEST_CASE("render option table: --repeat and --warm-up take at most kMaxFrames frames") {
    CHECK(given(vri::RenderTool::Render, {{"--repeat", "1000"}, {"--warm-up", "1000"}}).repeat == vri::kMaxFrames);
    CHECK(given(vri::RenderTool::Reference, {{"--warm-up", "0"}}).warmUp == 0);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Render, {{"--repeat", "1001"}}),
                         "--repeat: expected a whole number from 1 to 1000, got '1001'", vri::Error);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Reference, {{"--repeat", "0"}}),
                         "--repeat: expected a whole number from 1 to 1000, got '0'", vri::Error);
    CHECK_THROWS_WITH_AS(given(vri::RenderTool::Render, {{"--warm-up", "99999999999"}}),
                         "--warm-up: expected a whole number from 0 to 1000, got '99999999999'", vri::Error);
}

TEST_CASE("render option table: the settings record names what applies to the method") {
    CHECK(names(vri::settingsRecord(vri::RenderRequest(vri::RenderTool::Render))) ==
          std::set<std::string>{"method", "placement", "sampling_rate", "step_voxels", "precision", "simd",
                                "early_termination", "skip_empty_space", "clamp", "tile_size"});
    CHECK(names(vri::settingsRecord(given(vri::RenderTool::Render, {{"--method", "coupled"}}))) ==
          std::set<std::string>{"method", "precision", "simd", "early_termination", "tolerance", "h0_voxels",
                                "h_min_voxels", "h_max_voxels", "accepted_value", "skip_empty_space", "clamp", "tile_size"});
    CHECK(names(vri::settingsRecord(vri::RenderRequest(vri::RenderTool::Reference))) ==
          std::set<std::string>{"method", "precision", "tolerance", "clamp", "tile_size"});
    for (const vri::Setting& s : vri::settingsRecord(given(vri::RenderTool::Render, {{"--method", "decoupled"},
                                                                                    {"--h-max", "none"}})))
        if (s.name == "h_max_voxels") CHECK(std::get<std::string>(s.value) == "none");
}
