#pragma once
// vri-run's Slurm executor (README "On a cluster"): the steps that must run are submitted at once
// as batch jobs, bundled by their price (slurm_jobs.h), each job depending on the jobs that write its
// inputs (--dependency=afterok), so that the cluster, not vri-run, orders the work. Each job runs
// `vri-run --slurm-node-steps` (slurm_node.h), which runs the exact commands of the local executor
// and leaves a status file per step; vri-run watches the jobs with squeue and, as each ends, records
// its steps in the step cache and the manifest as the local executor does, with the job's id, node
// and state. Caching, the manifest and the images are the local executor's: the same commands on
// the same files.
#include <cstddef>
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

#include "libvri/experiment/experiment_run.h"

namespace vri {

// Runs the plan on Slurm. A step whose dependencies all come from the cache is looked up in the cache
// as locally; one downstream of a step that runs is submitted too (its inputs do not exist yet to be
// compared). A job that fails, times out, is preempted or cancelled fails its steps with one line
// naming the job and Slurm's state; the jobs that depend on it are cancelled and their steps do not
// run. SIGINT, SIGTERM or SIGHUP to vri-run cancels every job it submitted (scancel) and waits for
// them to end before it returns with a vri::Error.
//
// Before the first job of a vri-run (options.slurm.nodesChecked), one small job checks that a compute
// node sees the tools (SHA-512 of every vri-* program in the tool folder), the plan's existing inputs
// (sizes) and the results root (it writes its report there) as this host does; anything else is a
// vri::Error with the first problem, and nothing is submitted.
std::vector<StepOutcome> runPlanOnSlurm(const Plan& plan, const RunOptions& options, FileHasher& hasher);

// Several plans at once, as runPlanOnSlurm runs one: every plan's jobs are submitted before any is
// watched, so that the cluster runs the experiments side by side. SIGINT, SIGTERM and SIGHUP are
// caught while the batch lives.
class SlurmBatch {
public:
    SlurmBatch(const RunOptions& options, FileHasher& hasher);
    ~SlurmBatch();
    SlurmBatch(const SlurmBatch&) = delete;
    SlurmBatch& operator=(const SlurmBatch&) = delete;

    // Takes a plan (kept by reference) with its steps' prices, settles what the cache vouches for and
    // cuts the rest into jobs: how many of its steps will run.
    std::size_t add(const Plan& plan, std::vector<std::optional<double>> prices);
    // The jobs of every plan added as run() would submit them, and their sbatch commands (SlurmRun::describe),
    // on `out`: vri-run --dry-run --executor slurm. Submits, cancels and writes nothing.
    void describe(std::ostream& out);
    // The node check, once a vri-run (options.slurm.nodesChecked), over every plan added.
    void checkNodes();
    // Submits every plan's jobs, then waits for them all. A plan's failed step fails that plan
    // (result()); an interrupt, a refused submission or squeue failing for minutes cancels every job
    // and is a vri::Error.
    void run();
    // Plan k's outcomes (in the order added), or a vri::Error with its first failure.
    std::vector<StepOutcome> result(std::size_t k) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vri
