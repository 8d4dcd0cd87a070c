#pragma once
// The command-line spellings the experiment planner writes into other tools' commands, declared by those
// tools with the same constants: vri-render's outputs, vri-outside's renderer, vri-merge-tiles, vri-diff,
// vri-tabulate and vri-plot. Spelled once, a renamed flag is a compile error in the tool and the planner
// alike, not a step that fails when it runs. The scene's flags are in core/scene_flags.h, the render
// options' in the rows of core/render_option_table.h; "-o" is every tool's output.
namespace vri {

namespace render_flag {
inline constexpr const char* png = "--png";
inline constexpr const char* stats = "--stats";
inline constexpr const char* log = "--log";
}  // namespace render_flag

namespace outside_flag {
inline constexpr const char* rendererImage = "--renderer-image";
inline constexpr const char* rendererName = "--renderer-name";
inline constexpr const char* timeout = "--timeout";
}  // namespace outside_flag

namespace merge_flag {
inline constexpr const char* tile = "--tile";
inline constexpr const char* layer = "--layer";
}  // namespace merge_flag

namespace diff_flag {
inline constexpr const char* threshold = "--threshold";
inline constexpr const char* failPercent = "--failpercent";
inline constexpr const char* warnPercent = "--warnpercent";
inline constexpr const char* json = "--json";
inline constexpr const char* diffImage = "--diff-image";
inline constexpr const char* diffScale = "--diff-scale";
inline constexpr const char* heatScale = "--heat-scale";
inline constexpr const char* heatTop = "--heat-top";
inline constexpr const char* heatSigned = "--heat-signed";
inline constexpr const char* scaleOver = "--scale-over";
inline constexpr const char* scaleFrom = "--scale-from";
inline constexpr const char* mask = "--mask";
inline constexpr const char* histogram = "--histogram";
}  // namespace diff_flag

namespace tabulate_flag {
inline constexpr const char* layout = "--layout";
inline constexpr const char* title = "--title";
inline constexpr const char* row = "--row";
inline constexpr const char* cell = "--cell";
inline constexpr const char* run = "--run";
inline constexpr const char* point = "--point";
inline constexpr const char* points = "--points";
inline constexpr const char* value = "--value";
inline constexpr const char* threshold = "--threshold";
inline constexpr const char* baseline = "--baseline";
inline constexpr const char* channels = "--channels";
inline constexpr const char* precision = "--precision";
inline constexpr const char* csv = "--csv";
}  // namespace tabulate_flag

namespace plot_flag {
inline constexpr const char* dataDir = "--data-dir";
}  // namespace plot_flag

}  // namespace vri
