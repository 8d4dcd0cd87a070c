// The starting study vri-run --new writes.
#include "libvri/experiment/new_study.h"

#include <filesystem>
#include <string>
#include <utility>

#include "libvri/experiment/experiment_spec.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// NAME in a template becomes the study's name.
std::string named(std::string text, const std::string& name) {
    for (std::size_t at = text.find("NAME"); at != std::string::npos; at = text.find("NAME", at + name.size()))
        text.replace(at, 4, name);
    return text;
}

constexpr const char* kExperiment = R"yaml(# NAME: a study of your own, written by vri-run --new; every key is in experiments/README.md.
#   build/bin/vri-run NAME.yaml                 renders, compares and tabulates into results/NAME/
#   results/NAME/speed.md                       seconds per frame against error, the Pareto front flagged
#   results/NAME/speed.png                      the same as a chart (NAME-plot.yaml)
#   build/bin/vri-run --dry-run NAME.yaml       the commands, to run or change by hand
name: NAME                  # the results folder: letters, digits, . _ + -
title: "NAME: speed against accuracy of Riemann sums and adaptive Simpson"   # optional: the file's name
# paper: {paper: B, item: Table I, says: what the paper shows}     # only when it reproduces a paper's item

scenes:
  field:
    field: linear           # paper A's analytic field f = (x + 1.5) / 3, so that this file runs anywhere;
    field_dims: [32, 32, 32] #  your data instead: volume: NAME_64x64x64_uint8.raw (relative to this file, else
                            #   to $VRI_DATA_DIR; .raw names carry dims and type, or .nhdr/.dat/.vdb/.mhd)
    tf: NAME-tf.yaml        # check one with vri-tf --check FILE (format: experiments/README.md)
    # convention: cell      # the default; node puts the corner voxels on the box corners
    # camera: {eye: [-40, 30, 60], target: [16, 16, 16], up: [0, 1, 0], fov: 30}   # default: the tools' framing
    size: [160, 120]        # width, height

references:
  exact: {method: exact}    # the accurate solution (with a per-pixel error bound) the runs are compared with

methods:                    # each list is a sweep: one run per value, its id the name and the value
                            # warm_up, repeat: one untimed frame, then the median of 3 timed ones
  riemann: {method: riemann, step: [2, 1, 0.5, 0.25, 0.125], warm_up: 1, repeat: 3}   # fixed steps, in voxels
  coupled: {method: coupled, eps: [0.01, 0.001, 0.0001], warm_up: 1, repeat: 3}     # paper B's adaptive Simpson

comparisons:
  vs-exact: {reference: exact}   # vri-diff of every method run against exact: % of pixel-channels above
                                 #   0.01, 0.005 and 0.001, max and mean error

tables:
  speed:                    # one row per run: seconds, % above the threshold, max error, Pareto flags
    layout: tradeoff
    title: "NAME: seconds per frame against error"
    comparisons: [vs-exact]
    threshold: 0.001

figures:
  speed: {spec: NAME-plot.yaml, data: [speed.csv]}
)yaml";

constexpr const char* kTransferFunction = R"yaml(# NAME's transfer function (format: experiments/README.md, "Transfer functions").
description: A soft ramp with a sharp, bright band in the middle.
points:                     # [s, r, g, b, tau]: s is the voxel value over its range, tau the extinction per voxel
  - [0.00, 0.0, 0.0, 0.0, 0.0]
  - [0.40, 0.2, 0.4, 0.9, 0.3]
  - [0.50, 1.0, 0.9, 0.3, 2.0]
  - [0.60, 0.2, 0.4, 0.9, 0.3]
  - [1.00, 0.9, 0.9, 0.9, 0.6]
)yaml";

constexpr const char* kPlot = R"yaml(# NAME's chart (vri-plot --help has every key): the tradeoff table's CSV, one series per method family.
title: "NAME: seconds per frame against the largest error"
size: [900, 600]
panels:
  - x: {label: seconds per frame, log: true}
    y: {label: "largest error (any channel)", log: true}
    pareto: true            # joins the runs that no other run beats in both
    series:
      - {file: speed.csv, x: seconds, y: max, style: linespoints, label: riemann, where: {method: riemann double}}
      - {file: speed.csv, x: seconds, y: max, style: linespoints, label: coupled, where: {method: coupled double}}
)yaml";

}  // namespace

std::vector<fs::path> writeNewStudy(const fs::path& path) {
    std::string name = path.filename().string();
    if (name.ends_with(".yaml")) name.resize(name.size() - 5);
    if (!isSafeName(name)) throw Error("--new: '" + name + "' must be " + std::string(kSafeName));
    const fs::path dir = path.parent_path();
    // The transfer function and the plot first, the experiment that names them last: a study's file is never
    // there without its parts.
    const std::vector<std::pair<fs::path, std::string>> files{
        {dir / (name + "-tf.yaml"), named(kTransferFunction, name)},
        {dir / (name + "-plot.yaml"), named(kPlot, name)},
        {dir / (name + ".yaml"), named(kExperiment, name)}};
    for (auto it = files.rbegin(); it != files.rend(); ++it)  // the experiment's name first
        if (const fs::path& file = it->first; fs::exists(file) || fs::is_symlink(file))
            throw Error("--new: " + file.string() + " exists (choose another name; nothing was written)");
    // Every file staged beside its target before any is renamed into place (writeTogether): a full disk fails
    // while staging and places none, and nothing is removed that another writer may have put there since.
    OutputSet study;
    std::vector<fs::path> written;
    for (const auto& [file, text] : files) {
        study.add(file, text);
        written.push_back(file);
    }
    try {
        study.write();
    } catch (const Error& e) {
        throw Error("--new: " + std::string(e.what()) + " (nothing of the study was written)");
    }
    return written;
}

}  // namespace vri
