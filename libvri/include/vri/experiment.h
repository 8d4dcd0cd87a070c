#pragma once
// An experiment file (experiments/*.yaml, schema in experiments/README.md), validated on load and
// expanded: every parameter sweep is multiplied out into runs with stable, readable ids.
//
// Values that end up on a tool's command line are kept as the scalar text of the YAML file
// ("0.5", not 0.500000), so that the commands a reader sees are the ones the file reads.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vri {

// One command-line option of a tool: {"--step", "0.5"}; an empty value is a flag ("--png-invert").
using ToolOption = std::pair<std::string, std::string>;
using ToolOptions = std::vector<ToolOption>;

struct PaperItem {
    std::string paper;  // "A" or "B"
    std::string item;   // "Fig. 4", "Table I"
    std::string says;   // one line: what the paper shows there
};

// What the images show: volume or analytic field, transfer function, camera, image size, preview.
struct SceneSpec {
    std::string name;
    std::string dataset;                    // catalog name, when the scene names one
    std::string datasetStatus, datasetNote;  // from the catalog: "exact", "reconstructed" or "stand-in", and why
    std::vector<std::filesystem::path> files;  // volume and transfer function, absolute: hashed for the cache
    ToolOptions options;                    // vri-render's scene options, paths as absolute paths
};

// One invocation of a run tool (vri-render today; vri-reference tomorrow): a point of a sweep.
struct RunSpec {
    std::string id;     // "riemann-entry-h0.5": prefix, then the value of each swept parameter
    std::string tool;   // "vri-render"
    std::string scene;  // SceneSpec::name
    bool reference = false;  // from `references:`: compared against, not compared by default
    std::vector<std::pair<std::string, std::string>> parameters;  // YAML key -> value, in file order
    ToolOptions options;  // the tool's method options
};

// One vri-diff of a run against a reference run.
struct ComparisonSpec {
    std::string id;  // "<comparison>-<run id>"
    std::string group;  // the comparison's name in the file
    std::string reference, run;  // RunSpec ids
    std::vector<std::string> thresholds;
    std::string diffImage;  // "", "png" or "exr"
    bool histogram = false;
};

// A table by vri-tabulate: either the % of pixels above each threshold, one row per run of some
// comparisons (paper B Tables I, II), or one value of each run's stats, one row per run (Table III).
struct TableSpec {
    std::string name, title;
    std::vector<std::string> comparisons;  // ComparisonSpec::group names (threshold layout)
    std::vector<std::string> runs;         // RunSpec ids (matrix layout)
    std::string value = "stats.wall_seconds";  // matrix layout: the dotted JSON path in the stats file
    std::string column = "seconds";            // matrix layout: its column heading
};

// A figure drawn by vri-plot from a plot spec (relative to the experiment file) and tables' CSV.
struct FigureSpec {
    std::string name;
    std::filesystem::path spec;  // absolute
    std::vector<std::string> tables;  // TableSpec names whose CSV the plot reads
};

// A number the reproducibility check recomputes from a quick run and compares with the committed one.
struct ReproduceCheck {
    std::string of;  // a RunSpec id (image metrics: max, mean) or a ComparisonSpec id (max_abs, mean_abs, rmse)
    std::vector<std::string> metrics;
    double tolerance = 0;  // absolute, per channel
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
    std::vector<TableSpec> tables;
    std::vector<FigureSpec> figures;
    std::vector<ReproduceCheck> reproduce;

    const SceneSpec& scene(const std::string& name) const;
    const RunSpec& run(const std::string& id) const;
};

// Parses and validates; every problem is a vri::Error "file:line:col: ...". Relative paths are
// resolved against `baseDir` (the experiment file's folder) and must exist. With `quick`, the
// file's quick: block is merged over it first (maps merge key by key, anything else replaces).
Experiment parseExperiment(const std::string& yamlText, const std::string& source,
                           const std::filesystem::path& baseDir, bool quick);
Experiment loadExperiment(const std::filesystem::path& path, bool quick);

}  // namespace vri
