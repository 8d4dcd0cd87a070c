#pragma once
// An experiment file (experiments/*.yaml, schema in experiments/README.md), validated on load and
// expanded: every parameter sweep is multiplied out into runs with stable, readable ids.
//
// Values that end up on a tool's command line are kept as the scalar text of the YAML file
// ("0.5", not 0.500000), so that the commands a reader sees are the ones the file reads.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/io/volume_read_options.h"

namespace vri {

// One command-line option of a tool: {"--step", "0.5"}; an empty value is a flag ("--png-invert").
// Where an experiment file names options by key, a one-letter key is "-o", any other "--summary".
using ToolOption = std::pair<std::string, std::string>;
using ToolOptions = std::vector<ToolOption>;

// `paper:` is optional: an own study has none (paper "none", item and says empty).
struct PaperItem {
    std::string paper = "none";  // "A", "B" or "none"
    std::string item;            // "Fig. 4", "Table I"; optional with paper none
    std::string says;            // one line: what the paper shows there; optional with paper none
};

// What the images show: volume or analytic field, transfer function, camera, image size, preview.
struct SceneSpec {
    std::string name;
    std::string dataset;                    // catalog name, when the scene names one
    std::string datasetStatus, datasetNote;  // from the catalog: "exact", "reconstructed" or "stand-in", and why
    std::vector<std::filesystem::path> files;  // volume and transfer function, absolute: hashed for the cache
    // A header volume's data file (.nhdr's .raw, .mhd's data, .dat's raw file), absolute: the render reads it
    // too, so its digest keys the step's cache with the header's.
    std::vector<std::filesystem::path> dataFiles;
    ToolOptions options;                    // vri-render's scene options, paths as absolute paths
    int width = 800, height = 600;          // the images' size: `size:`, else vri-render's default --size
    // Its volume's dims and voxel type where a brick reads its box alone: the catalog's raw file, a `volume:`
    // file's (io's brickedShape: a raw file named by the Open SciVis convention, a header whose voxels are
    // stored as vri keeps them, a TIFF stack of such pages); none for another file, an analytic field, or a
    // name vri-render will refuse.
    std::optional<VolumeShape> volumeShape;
};

// The most runs the sweeps of one experiment file may expand to (the largest of experiments/ has
// under 100): a few lines of YAML can multiply out to 10^8 runs, refused before expanding.
inline constexpr std::uint64_t kMaxRuns = 10000;
// The most tiles one run may be split into (`tiles:`): each is a process and a step of its own.
inline constexpr int kMaxTiles = 256;

// One invocation of a run tool (vri-render today; vri-reference tomorrow): a point of a sweep.
struct RunSpec {
    std::string id;     // "riemann-entry-h0.5": prefix, then the value of each swept parameter
    std::string tool;   // "vri-render"
    std::string scene;  // SceneSpec::name
    bool reference = false;  // from `references:`: compared against, not compared by default
    std::vector<std::pair<std::string, std::string>> parameters;  // YAML key -> value, in file order
    ToolOptions options;  // the tool's method options
    // `tiles: N`: the image rendered as N bands of rows, one step each (--region), then merged by
    // vri-merge-tiles into the files the untiled run writes (experiment_plan.h). Not part of the id.
    int tiles = 1;
    // `bricks: [NX, NY, NZ]`: the volume cut into a grid of bricks, each brick's layer a step of its own
    // (--bricks, --brick), then joined by vri-merge-tiles --layer into the files the unbricked run writes,
    // within the stated bound (docs/conventions/bricks.md). Not part of the id.
    glm::ivec3 bricks{1, 1, 1};
    // `renderer: NAME` (tool vri-outside): the renderer's command after --, with its placeholders, what it
    // writes at {output}, and the files the command names (its executable first), whose digests key the cache.
    std::vector<std::string> command;
    std::string rendererName, rendererImage, rendererTimeout;
    std::vector<std::filesystem::path> commandFiles;
};

// One vri-diff of a run against a reference run.
struct ComparisonSpec {
    std::string id;  // comparisonId(group, run, the run's scene)
    std::string group;  // the comparison's name in the file
    std::string reference, run;  // RunSpec ids
    std::vector<std::string> thresholds;
    std::string diffImage;  // "", "png" or "exr"
    std::string diffScale;  // vri-diff --diff-scale, as written; "" for none
    // `diff_scale: shared`: one heat-map scale for the whole comparison, the largest difference of any of
    // its runs (vri-diff --scale-over each other run's image, computed once: --scale-from).
    bool sharedScale = false;
    bool histogram = false;
    // vri-diff --mask: which pixels every statistic counts ("all", "hit", "alpha>T" or an image, from the
    // experiment's folder); "" for all.
    std::string mask;
    std::string heatScale;  // vri-diff --heat-scale of a PNG heat map: "", "log" or "log:N"
    std::string heatTop;    // vri-diff --heat-top: "" (the largest error) or "pN"
    bool heatSigned = false;  // vri-diff --heat-signed
};

// A comparison's id, the name of its files: its name and the run's id, with the words (between '-') that
// the name ends with and the run's id starts with written once, when they begin with the run's scene:
// vs-exact-bonsai and bonsai-riemann-h0.5 make vs-exact-bonsai-riemann-h0.5. Other shared words stay twice,
// so that the run's id is whole in the file name: vs-exact of run exact-tol1e-4 is vs-exact-exact-tol1e-4,
// never vs-exact-tol1e-4 (which reads as a comparison against "exact-tol"). The name keeps a word of its own.
std::string comparisonId(const std::string& name, const std::string& run, const std::string& scene);

// One invocation of any vri tool that writes data files (vri-rays2d, ...), from `commands:`: the step
// that stands for it is called `name`. Its inputs are source files, its outputs land in the results folder.
struct CommandSpec {
    std::string name;
    std::string tool;     // "vri-rays2d"
    ToolOptions options;  // in file order; lists joined by commas, true as a flag, false left out
    std::vector<std::pair<std::string, std::filesystem::path>> inputs;  // option -> file (absolute), hashed
    std::vector<std::pair<std::string, std::string>> outputs;  // option -> file name in results/<experiment>/
    // `renderer: NAME` (vri-verify, vri-outside): that renderer's command after --, as RunSpec's; `scene: NAME`:
    // that scene's options (its volume, transfer function, camera and size), as a render of it takes them.
    std::string scene;
    std::vector<std::string> command;
    std::string rendererName, rendererImage, rendererTimeout;
    std::vector<std::filesystem::path> commandFiles;
    int threads = 0;          // options: threads: N (0: the tool's default, all cores)
    std::uint64_t pixels = 0;  // its scene's size, or options: size: WxH (0: neither)
};

// A table by vri-tabulate, in one of its layouts: "thresholds", the % of pixels above each threshold,
// one row per run of some comparisons (paper B Tables I, II); "matrix", one value of each run's stats,
// one row per run (Table III); "tradeoff", per run of some comparisons its seconds per frame against
// its errors at one threshold, the Pareto front flagged (paper B's speed against accuracy);
// "convergence", per series of compared runs that differ only in their step, the observed order.
struct TableSpec {
    std::string name, title;
    std::string layout;                    // "thresholds", "matrix", "tradeoff" or "convergence"
    std::vector<std::string> comparisons;  // ComparisonSpec::group names (thresholds and tradeoff layouts)
    std::vector<std::string> runs;         // RunSpec ids (matrix layout)
    // Thresholds layout, `rows:`: label -> the compared runs of the row, one for all thresholds or one
    // per threshold in order (paper B's adaptive rows: the run at eps = each threshold). Empty: one
    // row per compared run, labelled with its id.
    std::vector<std::pair<std::string, std::vector<std::string>>> rows;
    std::string value = "stats.wall_seconds";  // matrix layout: the dotted JSON path in the stats file
    std::string column = "seconds";            // matrix layout: its column heading
    // Tradeoff layout: the thresholds of its % columns as the file spells them (the first is the %
    // front's); `baseline:`, a compared run whose time the others' are divided by; `channels:`, "all"
    // or "worst" (only the worst channel's columns).
    std::vector<std::string> thresholds{"0.001"};
    std::string baseline;
    std::string channels = "all";
    std::string precision;  // decimals, "" for vri-tabulate's default
    bool byScene = false;  // matrix layout, `group_by: scene`: one column per scene, rows the runs without the scene
};

// A figure drawn by vri-plot from a plot spec (relative to the experiment file) and data files that
// other steps write into the results folder (tables' CSV, commands' outputs).
struct FigureSpec {
    std::string name;
    std::filesystem::path spec;     // absolute
    std::vector<std::string> data;  // file names in results/<experiment>/ that the plot reads
    std::string dataAt;             // "file:line:col" of `data:`, for the error when no step writes one
};

// A number the reproducibility check recomputes from a quick run and compares with the committed one.
// A run's image, a comparison's numbers, or every cell of a CSV file a command writes.
struct ReproduceCheck {
    std::string of;  // a RunSpec id (image metrics: max, mean) or a ComparisonSpec id (max_abs, mean_abs, rmse)
                     // or a CommandSpec name (with `file`)
    std::vector<std::string> metrics;
    std::string file;      // commands: one of its outputs, a CSV compared cell by cell
    double tolerance = 0;  // absolute, per channel or per cell
};

struct Experiment {
    std::filesystem::path source;  // the YAML file
    std::string name, title;
    PaperItem paper;
    std::string agreement;  // hand-written after looking at the results: where ours and the paper's agree or differ
    bool quick = false;     // the quick: overrides were applied
    std::vector<SceneSpec> scenes;
    std::vector<RunSpec> runs;
    std::vector<ComparisonSpec> comparisons;
    std::vector<CommandSpec> commands;
    std::vector<TableSpec> tables;
    std::vector<FigureSpec> figures;
    std::vector<ReproduceCheck> reproduce;
    // What the file left out and was filled in, one line each ("title: the file name 'study'", "scene 'h':
    // convention cell, the tools' default"): the manifest lists them.
    std::vector<std::string> defaults;
    // What vri-run warns of before running it (timing_defaults.h: a timed table on one frame).
    std::vector<std::string> warnings;

    const SceneSpec& scene(const std::string& name) const;
    const RunSpec& run(const std::string& id) const;
};

// Names become file names in the results folder (the experiment's folder, run ids, tables, figures,
// command outputs) and step ids in .steps/: letters, digits, '.', '_', '+' and '-', starting with a
// letter or a digit, never "..". So no name is a path, hidden, "." or "..", and none holds a quote,
// a blank, a shell or gnuplot character or a control character. Every name an experiment file gives
// is held to this, with an error naming the file, line, column and key.
bool isSafeName(std::string_view name);
// What a safe name is, for messages that refuse one.
inline constexpr std::string_view kSafeName =
    "letters, digits, '.', '_', '+' or '-', starting with a letter or digit, no '..'";

// Parses and validates; every problem is a vri::Error "file:line:col: ...". Relative paths are
// resolved against `baseDir` (the experiment file's folder) and must exist. With `quick`, the
// file's quick: block is merged over it first (maps merge key by key, anything else replaces).
// The step graph is checked too (planExperiment): a figure reading a file that no step writes fails here.
Experiment parseExperiment(const std::string& yamlText, const std::string& source,
                           const std::filesystem::path& baseDir, bool quick);
Experiment loadExperiment(const std::filesystem::path& path, bool quick);

}  // namespace vri
