#pragma once
// What a run of a plan knows of its steps, whichever executor runs them (experiment_run.h): each
// step's key, which steps the cache vouches for or cannot run, the records of those that ran, the
// progress lines and the first failure. The executors decide only where and when a step runs.
#include <cstddef>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_run.h"
#include "libvri/experiment/step_progress.h"

namespace vri {

class StepLedger {
public:
    StepLedger(const Plan& plan, const RunOptions& options, FileHasher& hasher);

    const Plan& plan() const { return plan_; }
    std::size_t size() const { return plan_.steps.size(); }
    bool settled(std::size_t i) const { return settled_[i]; }
    const StepOutcome& outcome(std::size_t i) const { return outcomes_[i]; }

    // Settles step i without running it when an upstream step's tool or its own is not built
    // (Unavailable) or, unless --force, when its cache record vouches for its outputs (Cached); true
    // when it must run. Call it once the steps it depends on are settled.
    bool needsRun(std::size_t i);
    // Settles step i as Unavailable: an upstream step is.
    void settleUnavailable(std::size_t i);

    // Before step i runs: its old record goes (an interrupted run leaves nothing that vouches for
    // half-made outputs) and its folder is made. Returns the command's words; the step's log is logPath(i).
    std::vector<std::string> prepare(std::size_t i);
    // Step i's process has started (the local executor; a Slurm job's start is the cluster's).
    void started(std::size_t i) { progress_.started(i); }
    std::filesystem::path logPath(std::size_t i) const;  // <results>/.steps/<id>.log
    const std::filesystem::path& program(std::size_t i) const { return programs_[i]; }
    // The record of the digests of the plan's source files (input_digest.h), <results>/.steps/input-digests.json,
    // written as the first step is prepared: its steps take their inputs' digests from it (VRI_INPUT_DIGESTS).
    const std::filesystem::path& digestRecord() const { return digestRecord_; }

    // Step i ran and exited 0: its outputs are digested, its record written, its log removed. A
    // declared output that is missing fails it instead: false then.
    bool succeeded(std::size_t i, double wallSeconds, const StepExecution& execution);
    // Step i failed: `why` says how ("exit status 3", "Slurm job 12 TIMEOUT on node n1"); the first
    // failure is what run() reports, with the command and the step's log.
    void failed(std::size_t i, const std::string& why, double wallSeconds);
    // Step i will not run because `why` (a step it depends on failed); it counts as settled.
    void abandoned(std::size_t i, const std::string& why);

    bool hasFailure() const { return !failure_.empty(); }
    // The outcomes, or a vri::Error with the first failure.
    std::vector<StepOutcome> result() const;

private:
    void settle(std::size_t i, StepOutcome::State state, const std::string& how, const std::string& detail);
    // A render's stats that say it was timed beside other processes' load (timing.load): a warning line.
    void warnIfTimedUnderLoad(std::size_t i);

    const Plan& plan_;
    const RunOptions& options_;
    FileHasher& hasher_;
    std::filesystem::path digestRecord_;
    bool digestRecordWritten_ = false;
    std::vector<StepOutcome> outcomes_;
    std::vector<bool> settled_;
    std::vector<std::string> keys_;
    std::vector<std::filesystem::path> programs_;
    StepProgress progress_;
    std::set<std::string> missingTools_;
    std::string failure_;  // the first failed step's command and output
};

}  // namespace vri
