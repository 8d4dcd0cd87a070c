#pragma once
// Running a plan: each step as its own process (the exact command a reader would type), skipping
// those the step cache vouches for. Where the processes run is the executor's choice: vri-run's own
// children, up to `jobs` at once (local), or jobs of a Slurm cluster (slurm_executor.h).
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/slurm_profile.h"
#include "libvri/experiment/step_cache.h"

namespace vri {

enum class Executor { Local, Slurm };

// How steps become Slurm jobs (README "On a cluster").
struct SlurmOptions {
    std::vector<std::string> sbatchArguments;  // the site's and the user's, after vri-run's own (so they win)
    double bundleSeconds = 60;  // steps estimated below this share jobs of about this many seconds; 0: a job each
    int cpus = 2;               // CPUs of a step that does not set its own --threads
    double pollSeconds = 1;     // how often squeue is asked
    // --slurm-max-pending: give up once no job has run this long while some pend for the cluster (0: never).
    double maxPendingSeconds = 0;
    // --slurm-max-outage: how long squeue may fail in a row (a controller restarting or out of reach) before
    // vri-run gives up and cancels its jobs.
    double maxOutageSeconds = 120;
    // --slurm-retries: how many times a job that ended NODE_FAIL, PREEMPTED, BOOT_FAIL, LAUNCH_FAILED, TIMEOUT (with
    // --time doubled) or OUT_OF_MEMORY (with --mem doubled) is submitted again.
    int retries = 0;
    // --slurm-max-jobs: at most this many of the run's jobs in the queue at once, the next submitted as one
    // ends (0: all at once).
    std::size_t maxJobs = 0;
    // A site profile's resources per kind of step (slurm_profile.h), in place of the estimates.
    std::map<std::string, StepKindResources> kinds;
    // --dry-run: the jobs are described (SlurmBatch::describe), never submitted; nothing in the queue is touched.
    bool dryRun = false;
    // Whether a job has checked that the nodes share this host's files (slurm_executor.h): once a
    // vri-run, before its first submitted job. Shared by the copies of these options.
    std::shared_ptr<bool> nodesChecked = std::make_shared<bool>(false);
};

struct RunOptions {
    std::filesystem::path toolDir;  // where vri-render, vri-diff, ... are
    int jobs = 1;                   // steps run at once (local)
    bool force = false;             // run every step, cached or not
    bool quiet = false;             // no progress lines (step_progress.h)
    Executor executor = Executor::Local;
    SlurmOptions slurm;
    // Per step of the plan, its wall time in the last manifest (step_costs.h), when known: what a
    // Slurm job asks for as its time limit, how steps are bundled, and the progress line's ETA.
    std::vector<std::optional<double>> prices;
};

struct StepOutcome {
    enum class State { Ran, Cached, Unavailable } state = State::Ran;  // Unavailable: its tool is not built
    StepRecord record;  // of this run or, when cached, of the run that made the outputs
};

// Runs the steps in dependency order. A step whose tool is not built is reported on stderr and
// skipped with everything that depends on it. When a step fails, the steps already running finish
// (locally) and the steps that depend on it do not run; a vri::Error carries the failed command and
// its output. Progress goes to stderr (step_progress.h) unless options.quiet.
std::vector<StepOutcome> runPlan(const Plan& plan, const RunOptions& options, FileHasher& hasher);

}  // namespace vri
