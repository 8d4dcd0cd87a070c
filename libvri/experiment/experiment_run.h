#pragma once
// Running a plan: each step as its own process (the exact command a reader would type), up to
// `jobs` at once, skipping those the step cache vouches for.
#include <filesystem>
#include <vector>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/step_cache.h"

namespace vri {

struct RunOptions {
    std::filesystem::path toolDir;  // where vri-render, vri-diff, ... are
    int jobs = 1;                   // steps run at once
    bool force = false;             // run every step, cached or not
};

struct StepOutcome {
    enum class State { Ran, Cached, Unavailable } state = State::Ran;  // Unavailable: its tool is not built
    StepRecord record;  // of this run or, when cached, of the run that made the outputs
};

// Runs the steps in dependency order. A step whose tool is not built is reported on stderr and
// skipped with everything that depends on it. When a step fails, the steps already running finish,
// and a vri::Error carries the failed command and its output. Progress lines go to stderr when it
// is a terminal.
std::vector<StepOutcome> runPlan(const Plan& plan, const RunOptions& options, FileHasher& hasher);

}  // namespace vri
