#pragma once
// Every render option, declared once: its command-line spelling, its key in experiment files, how its
// value is checked and where it lands, which tools and backend take it, and what the stats file's
// settings record says about it. vri-render's and vri-reference's command lines (tools/common), the
// experiment reader's keys and checks, and the stats JSON are all read off this table; a new render
// option is one more row in render_option_table.cpp and a field of RenderRequest.
//
// The table is plain data, below any command-line library: tools/common turns its rows into CLI11
// options, the experiment reader into keys.
#include <optional>
#include <span>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "libvri/core/backend.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/exact_reference.h"

namespace vri {

// The most frames --repeat and --warm-up (repeat, warm_up) may ask for: every frame keeps its timing
// and is compared with the first, so memory and time grow with the count; 1000 frames give a median
// far tighter than a machine's noise.
inline constexpr int kMaxFrames = 1000;
// The most frames one run renders in all, (--warm-up + --repeat) x --frames: each option within its own
// limit, together they could ask for two million (hours of a test blob, days at 800 x 600) without a word.
inline constexpr long long kMaxRenderedFrames = 10000;

// --region's spelling, which the experiment planner writes into a tile's command (the row has no key: a
// region is the planner's, never an experiment file's).
inline constexpr const char* kRegionFlag = "--region";

// The tools that render: vri-render (every method, either backend) and vri-reference (the exact
// method, or paper B's reference: Riemann, entry placement, double, a 0.01-voxel step).
enum class RenderTool : unsigned { Render = 1, Reference = 2 };

// Everything a render is asked for, as the rows of the table fill it in from their defaults and the
// values given.
struct RenderRequest {
    explicit RenderRequest(RenderTool tool);

    RenderTool tool;
    bool exact = false;           // --method exact: vri-reference's method, in double on the CPU
    RenderOptions options;        // every other method's settings
    double exactTolerance = 0.0;  // --method exact's --tolerance (its own default, not the adaptive one's)
    // --method exact's --max-error: the largest per-pixel error bound asked for; the tool then searches the
    // tolerance that gives it (max_error_search.h), since the tolerance is per piece of a ray, not per pixel.
    std::optional<double> maxError;
    Backend backend = Backend::Cpu;
    std::string device;  // Vulkan: an index of --list-devices or part of a name; empty: the first
    VulkanInterpolation interpolation = VulkanInterpolation::Shader;
    int repeat = 1, warmUp = 0;  // timing: frames rendered, and untimed ones before them, each at most kMaxFrames
    bool clamp = false;          // clamp each pixel's colour and alpha to [0, 1] after the render
    std::vector<std::string_view> given;  // the flags of the options given, in the order given

    bool wasGiven(std::string_view flag) const;
    ExactReferenceOptions exactOptions() const;
};

// How an option's value is spelled: a command-line library converts Number and Count itself
// (and refuses what does not convert), passes Text as it is, and Flag takes no value ("true" here).
enum class OptionValueKind { Number, Count, Text, Flag };

// One named value of the stats file's settings record ("options" in a stats JSON).
using SettingValue = std::variant<bool, long long, double, std::string>;
struct Setting {
    std::string_view name;
    SettingValue value;
};

struct RenderOptionRow {
    std::string_view names;     // CLI11 spelling: "--tolerance,--eps"; the first name is the flag
    std::string_view key;       // in experiment files' methods and references; empty: command line only
    std::string_view idPrefix;  // how a swept value reads in a run id ("h" + "0.5"); empty: the value alone
    OptionValueKind kind;
    std::string_view help;
    std::string_view group;     // the help's option group ("adaptive"); empty: none
    std::string_view excludes;  // an option that cannot be given with this one; empty: none
    unsigned tools;             // RenderTool bits
    unsigned backends;          // 1 << Backend bits it applies to
    // Checks `text` and lands it in `request`; throws vri::Error "<where>: <what was expected>".
    void (*apply)(const std::string& text, const std::string& where, RenderRequest& request);
    // The default shown in --help for `request` (a tool's defaults); empty: none shown.
    std::string (*shownDefault)(const RenderRequest& request);
    // Appends what the stats file says about this option's setting (nothing where it does not apply).
    void (*record)(const RenderRequest& request, std::vector<Setting>& settings);
    // Experiment files only: the values `text` stands for on this host (simd's `lower`: one run per SIMD
    // target below the best this CPU has), or nullopt when it is a value of its own. Null: no such value.
    std::optional<std::vector<std::string>> (*hostValues)(std::string_view text) = nullptr;

    std::string_view flag() const { return names.substr(0, names.find(',')); }
    bool takenBy(RenderTool tool) const { return (tools & unsigned(tool)) != 0; }
};

std::span<const RenderOptionRow> renderOptionTable();
// What a row's group is, for --help ("adaptive": "coupled and decoupled (paper B), steps in voxels").
std::string_view renderOptionGroupHelp(std::string_view group);
// The row of an experiment key, or nullptr.
const RenderOptionRow* findRenderOption(std::string_view key);

// After every given value is applied: the rules between options (--device needs --backend vulkan, the
// exact method has no step, ...), and what follows from them (Vulkan renders in float unless told
// otherwise). Throws vri::Error naming the options.
void finishRenderRequest(RenderRequest& request);

// The stats file's settings record: each row's settings, then the tile size.
std::vector<Setting> settingsRecord(const RenderRequest& request);

}  // namespace vri
