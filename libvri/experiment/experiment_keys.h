#pragma once
// The keys an experiment file may hold, section by section: the reader refuses any other (yaml::requireKeys),
// and experiments/README.md documents each (tests/unit/experiment_keys_test.cpp checks that it does). A method's
// and a reference's keys are the render option table's (render_option_table.h) and methodKeysBesideOptions.
#include <array>
#include <string_view>
#include <utility>
#include <vector>

namespace vri {

// the file
inline constexpr std::array<std::string_view, 14> kTopLevelKeys{"name", "title", "paper", "agreement", "scenes", "renderers", "methods", "references", "comparisons", "commands", "tables", "figures", "reproduce", "quick"};
// paper:
inline constexpr std::array<std::string_view, 3> kPaperKeys{"paper", "item", "says"};
// a scene
inline constexpr std::array<std::string_view, 10> kSceneKeys{"dataset", "volume", "field", "field_dims", "as_grid", "convention", "tf", "camera", "size", "png"};
// a scene's camera:
inline constexpr std::array<std::string_view, 6> kCameraKeys{"eye", "target", "up", "fov", "zoom", "zoom_centre"};
// a scene's png:
inline constexpr std::array<std::string_view, 3> kPngKeys{"invert", "exposure", "background"};
// a renderers: entry
inline constexpr std::array<std::string_view, 3> kRendererKeys{"command", "image", "timeout"};
// a comparison
inline constexpr std::array<std::string_view, 10> kComparisonKeys{"reference", "runs", "thresholds", "diff_image", "diff_scale", "heat_scale", "heat_top", "heat_signed", "histogram", "mask"};
// a command
inline constexpr std::array<std::string_view, 6> kCommandKeys{"tool", "options", "inputs", "outputs", "renderer", "scene"};
// a table
inline constexpr std::array<std::string_view, 12> kTableKeys{"title", "layout", "comparisons", "runs", "rows", "value", "column", "group_by", "threshold", "baseline", "channels", "precision"};
// a figure
inline constexpr std::array<std::string_view, 2> kFigureKeys{"spec", "data"};
// reproduce:
inline constexpr std::array<std::string_view, 2> kReproduceKeys{"tolerance", "checks"};
// a reproduce: check
inline constexpr std::array<std::string_view, 4> kReproduceCheckKeys{"of", "metrics", "file", "tolerance"};
// quick:
inline constexpr std::array<std::string_view, 8> kQuickKeys{"title", "scenes", "methods", "references", "comparisons", "commands", "tables", "figures"};

// The keys of a methods: or references: entry that are not render options.
inline constexpr std::array<std::string_view, 4> kMethodKeysBesideOptions{"scenes", "tiles", "bricks", "renderer"};

// Every key, as (where, key): each section's above, then the methods' (the render option table's keys too).
std::vector<std::pair<std::string_view, std::string_view>> experimentKeys();

}  // namespace vri
