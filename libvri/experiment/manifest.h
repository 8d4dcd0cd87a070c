#pragma once
// The manifest of an experiment's results (<results>/manifest.json): what the experiment shows,
// the source tree and build, the machine, and for every step its exact command, parameters,
// input and output digests and wall time. The gallery (gallery.h) is read from manifests.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_run.h"
#include "libvri/experiment/experiment_spec.h"

namespace vri {

// The git work tree that holds a file: its top folder, its HEAD commit, and whether tracked files
// outside results/ differ from that commit (untracked ones and results/ do not count). nullopt
// outside a work tree or without git.
struct WorkTree {
    std::filesystem::path top;
    std::string commit;
    bool modified = false;
};
std::optional<WorkTree> workTreeOf(const std::filesystem::path& file);

// Writes <plan.resultsDir>/manifest.json atomically.
void writeManifest(const Experiment& experiment, const Plan& plan, const std::vector<StepOutcome>& outcomes,
                   const std::filesystem::path& toolDir, FileHasher& hasher);

}  // namespace vri
