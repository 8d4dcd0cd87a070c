#pragma once
// An experiment as a graph of steps: each step is one exact command line of a small tool
// (vri-render, vri-diff, vri-tabulate, vri-plot, or any tool a `commands:` entry names) with the files
// it reads and writes. A step depends on the steps that write its inputs. A new kind of work is a new
// kind of step.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "libvri/core/image.h"
#include "libvri/experiment/experiment_spec.h"

namespace vri {

struct Step {
    std::string id;    // unique in its experiment: the run, comparison or command id, "table-<name>", "figure-<name>"
    std::string kind;  // "render", "diff", "command", "table", "figure"
    std::string tool;  // executable name, looked up in the tool directory
    std::vector<std::string> arguments;  // after the tool, paths relative to the directory the plan was made for
    std::vector<std::filesystem::path> inputs;   // files read (absolute)
    std::vector<std::filesystem::path> outputs;  // files written (absolute)
    std::vector<std::pair<std::string, std::string>> parameters;  // what the step stands for, for the manifest
    // What the step asks of a machine, for its Slurm job (slurm_jobs.h), set where the planner writes the
    // options: the threads it runs on (0: the tool's default, every core it is given) and the pixels it
    // renders (of its region, for a tile; 0: none).
    int threads = 0;
    std::uint64_t pixels = 0;
    // The bricks its volume is cut into, of which the step reads one (`bricks:`); 1 for the whole volume.
    int volumeParts = 1;
    // The voxel bytes the step holds, where the planner knows the volume's layout (the dataset catalog's, or
    // a raw file's name): the whole volume's for a render or a tile, a brick's own and its ghost layer's
    // for a brick (read by offset). 0 elsewhere: the Slurm estimate then goes by the files' sizes.
    std::uint64_t volumeBytes = 0;

    // Whether the local executor runs the step alone: an untiled, unbricked render or a command times itself
    // or the program it runs, and a neighbour would take cores from it. Tiles, bricks, merges, diffs, tables
    // and figures may run side by side (vri-run --jobs).
    bool alone = false;
};

struct Plan {
    std::filesystem::path resultsDir;  // results/<experiment> (absolute)
    std::filesystem::path workDir;     // commands are run from here; their relative paths start here
    std::vector<Step> steps;           // in an order where every step comes after those it depends on
    std::vector<std::vector<std::size_t>> dependencies;  // per step: the steps that write its inputs
    // Empty for a whole plan; else what part of the experiment's steps it holds and why (checkedPart), which
    // the manifest and the gallery say.
    std::string part = {};

    const Step& step(const std::string& id) const;
    // How the commands name `file`: relative to workDir when the two share more than the root, else absolute.
    std::string commandPath(const std::filesystem::path& file) const;
};

// Steps of an experiment whose outputs go to `resultsDir`; the commands name files relative to `workDir`
// when the two share more than the root (else absolutely), so that they can be pasted in a shell there.
Plan planExperiment(const Experiment& experiment, const std::filesystem::path& resultsDir,
                    const std::filesystem::path& workDir);

// The words of a step's command: the tool (in `toolDir`, relative to the plan's workDir), then its arguments.
std::vector<std::string> commandWords(const Plan& plan, const Step& step, const std::filesystem::path& toolDir);
// The same, as one line a POSIX shell reads back into those words.
std::string shellCommand(const std::vector<std::string>& words);

// A run's tiles (`tiles: n`, n <= height): n bands of whole rows, top to bottom, balanced in rows (heights
// differ by at most one), not in cost. Bands keep each tile one rectangle whose pixels lie together in
// memory, and any n up to the height divides the image.
std::vector<PixelRegion> rowBands(int width, int height, int n);

// The output files of a step by kind of content, for the manifest and the gallery.
std::filesystem::path renderImage(const Plan& plan, const std::string& runId);  // <results>/<run>.exr

}  // namespace vri
