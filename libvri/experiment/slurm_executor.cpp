// The Slurm executor: submitting a plan's jobs, watching them, cancelling them.
#include "libvri/experiment/slurm_executor.h"

#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>

#include "libvri/experiment/poll_interval.h"
#include "libvri/experiment/slurm_commands.h"
#include "libvri/experiment/slurm_jobs.h"
#include "libvri/experiment/slurm_node.h"
#include "libvri/experiment/slurm_pending.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/experiment/step_ledger.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"
#include "libvri/util/format.h"
#include "libvri/util/own_folder.h"
#include "libvri/util/process.h"

namespace vri {

namespace fs = std::filesystem;

// Named, not anonymous: SlurmBatch::Impl, a type of the header's, holds these (-Wsubobject-linkage).
namespace slurm_detail {

using Clock = std::chrono::steady_clock;

// How long a file a finished job wrote may take to show here (a network file system's attribute cache).
constexpr double kSharedFileDelaySeconds = 30;
// --slurm-retries: what a retry after TIMEOUT multiplies the job's --time by, after OUT_OF_MEMORY its --mem.
constexpr double kRetryFactor = 2.0;
// After scancel, how long vri-run waits for its jobs to end before it stops waiting.
constexpr double kCancelWaitSeconds = 60;
// The state of a job squeue has forgotten (it ended long ago: MinJobAge).
const std::string kForgotten = "ENDED";
// squeue's reason for a job Slurm holds after its node could not launch it (slurmd failed to start it: a
// prolog, the user's environment, a fork), and vri-run's state for such a job once it has cancelled it.
const std::string kLaunchFailedReason = "launch failed requeued held";
// Held after a failed launch: squeue shows it PENDING, or COMPLETING while its node's epilog runs, its restart
// count raised by a requeue that does not run it again.
bool heldAfterFailedLaunch(const SlurmJob& job) {
    return !isFinalJobState(job.state) && job.reason == kLaunchFailedReason;
}
const std::string kLaunchFailed = "LAUNCH_FAILED";

extern "C" void onInterrupt(int signal) { gSlurmInterrupt = signal; }

// SIGINT, SIGTERM and SIGHUP set gSlurmInterrupt (slurm_commands.h) while it lives, so that vri-run cancels its jobs before it exits.
class InterruptGuard {
public:
    InterruptGuard() {
        gSlurmInterrupt = 0;
        struct sigaction action = {};
        action.sa_handler = onInterrupt;
        sigemptyset(&action.sa_mask);
        for (std::size_t k = 0; k < kSignals.size(); ++k) sigaction(kSignals[k], &action, &old_[k]);
    }
    ~InterruptGuard() {
        for (std::size_t k = 0; k < kSignals.size(); ++k) sigaction(kSignals[k], &old_[k], nullptr);
    }
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    static constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};
    std::array<struct sigaction, 3> old_{};
};

// Sleeps, but returns early when a signal arrives (nanosleep's EINTR), so that an interrupt is seen at once.
void pause(double seconds) {
    timespec t{static_cast<time_t>(seconds), static_cast<long>((seconds - static_cast<time_t>(seconds)) * 1e9)};
    ::nanosleep(&t, nullptr);
}

std::string signalName(int signal) {
    switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    }
    return "signal " + std::to_string(signal);
}

// Job ids as a reader takes them in: runs of consecutive ids as "12-40", then how many ("12-40,45 (30 jobs)").
std::string jobList(const std::vector<std::string>& ids) {
    std::vector<long long> numbers;
    for (const std::string& id : ids) numbers.push_back(std::stoll(id));  // sbatch's ids: digits only
    std::sort(numbers.begin(), numbers.end());
    std::string text;
    for (std::size_t i = 0; i < numbers.size();) {
        std::size_t j = i;
        while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
        if (!text.empty()) text += ',';
        text += std::to_string(numbers[i]);
        if (j > i) text.append(1, '-').append(std::to_string(numbers[j]));
        i = j + 1;
    }
    text.append(" (").append(std::to_string(ids.size())).append(ids.size() == 1 ? " job)" : " jobs)");
    return text;
}

// The job script: it runs its arguments as one command. The names and paths of a step reach the
// node as arguments of sbatch and of this script, never as text a shell reads.
void writeJobScript(const fs::path& script) {
    writeTextFile(script, "#!/bin/sh\n# vri-run's Slurm job: runs its arguments as one command.\nexec \"$@\"\n");
}

// Cancels `jobs`, waits until squeue shows them ended (or no longer knows them), at most kCancelWaitSeconds,
// and says what became of them, to end an error message: "cancelled Slurm jobs 4-6 (3 jobs)", or, where
// scancel failed and squeue cannot show them ended, that they may still run and how to cancel them. scancel
// is asked again while squeue shows them running.
struct CancelOutcome {
    bool cancelled;
    std::string said;
};
// An error message holds at most printable.h's limit: a longer scancel command goes on a line of its own.
constexpr std::size_t kInlineCommandBytes = 400;
CancelOutcome cancelAndWait(const std::vector<std::string>& jobs, double pollSeconds) {
    if (jobs.empty()) return {true, "no Slurm job was left to cancel"};
    const CancelOutcome cancelled{true, "cancelled Slurm jobs " + jobList(jobs)};
    std::string refused = cancelJobs(jobs);
    const auto couldNot = [&](bool controllerSilent) {
        std::string command = "scancel";
        for (const std::string& id : jobs) command += ' ' + id;
        std::string how = "'" + command + "'";
        if (command.size() > kInlineCommandBytes) {
            std::cerr << "vri-run: " << command << '\n';
            how = "the scancel command on the line above";
        }
        return CancelOutcome{false, "could not cancel Slurm jobs " + jobList(jobs) + " (" + refused +
                                        "): they may still run; cancel them with " + how +
                                        (controllerSilent ? " once the controller answers" : "")};
    };
    const auto start = Clock::now();
    bool said = false;  // a wait longer than a few seconds says what it waits for
    for (double waited = 0; waited < kCancelWaitSeconds; waited = std::chrono::duration<double>(Clock::now() - start).count()) {
        if (!said && waited > 5) {
            std::cerr << "vri-run: waiting for cancelled Slurm jobs " << jobList(jobs) << " to end (at most "
                      << kCancelWaitSeconds << " s)\n";
            said = true;
        }
        std::map<std::string, SlurmJob> states;
        try {
            states = queryJobs(jobs, false);  // after a signal too: that is when this wait matters
        } catch (const Error&) {
            // The controller does not answer: what scancel said is all there is to go by.
            return refused.empty() ? cancelled : couldNot(true);
        }
        bool running = false;
        try {
            for (const auto& [id, job] : states) running = running || !isFinalJobState(job.state);
        } catch (const Error&) {
            // A state this vri-run does not know: only scancel's answer tells.
            return refused.empty() ? cancelled : couldNot(false);
        }
        if (!running) return cancelled;
        if (!refused.empty()) refused = cancelJobs(jobs);
        pause(pollSeconds);
    }
    return refused.empty() ? cancelled : couldNot(false);
}

// Runs `watch`; whatever stops it, `unended()` (the jobs still to end then) are cancelled and the error says
// what became of them: a vri::Error is thrown again with the outcome appended, anything else (out of memory,
// a file system error) is rethrown as it is, the outcome on a line of its own.
template <class Unended, class Watch>
void cancelOnFailure(double pollSeconds, const Unended& unended, const Watch& watch) {
    try {
        watch();
    } catch (const Error& e) {
        const std::vector<std::string> jobs = unended();
        if (jobs.empty()) throw;
        throw Error(std::string(e.what()) + "; " + cancelAndWait(jobs, pollSeconds).said);
    } catch (...) {
        if (const std::vector<std::string> jobs = unended(); !jobs.empty())
            std::cerr << "vri-run: " << cancelAndWait(jobs, pollSeconds).said << '\n';
        throw;
    }
}

// How long squeue has failed in a row, against --slurm-max-outage: a controller restarting or out of reach
// for a while does not stop the run (its jobs run on without it); one line says squeue fails, another when it
// answers again. The clock starts when the first failing look was asked.
class SqueueOutage {
public:
    explicit SqueueOutage(double maxSeconds) : maxSeconds_(maxSeconds) {}

    // squeue, asked at `asked`, failed with `e`: rethrown past the limit, else said once.
    void failed(const Error& e, Clock::time_point asked) {
        if (!since_) since_ = asked;
        const double silent = std::chrono::duration<double>(Clock::now() - *since_).count();
        if (silent >= maxSeconds_)
            throw Error(std::string(e.what()) + "; no answer for " + secondsText(silent) + " (--slurm-max-outage " +
                        exactNumber(maxSeconds_) + " s)");
        if (!said_)
            std::cerr << "vri-run: " << e.what() << "; asking again for up to " << exactNumber(maxSeconds_)
                      << " s (--slurm-max-outage) while the jobs run on\n";
        said_ = true;
    }
    void answered() {
        if (said_)
            std::cerr << "vri-run: squeue answers again after "
                      << secondsText(std::chrono::duration<double>(Clock::now() - *since_).count()) << '\n';
        since_.reset();
        said_ = false;
    }

private:
    double maxSeconds_;
    std::optional<Clock::time_point> since_;
    bool said_ = false;
};

// The jobs' states, or nullopt while squeue fails within the outage allowed; a signal that stopped squeue
// gives nullopt too, for the caller's first line to stop the run.
std::optional<std::map<std::string, SlurmJob>> lookAtJobs(const std::vector<std::string>& ids, SqueueOutage& outage) {
    const auto asked = Clock::now();
    try {
        std::map<std::string, SlurmJob> states = queryJobs(ids);
        outage.answered();
        return states;
    } catch (const Error& e) {
        if (!gSlurmInterrupt) outage.failed(e, asked);
        return std::nullopt;
    }
}

// The job files of the runs before this one kept beside it: the output of a job an error message named stays
// for a rerun or two.
constexpr std::size_t kKeptRuns = 3;

// Removes the job files (job-<token>-<n>.json and .out, regular files only) of all but the `keep` runs whose
// files are newest; anything else in the folder stays.
void pruneJobFiles(const fs::path& folder, std::size_t keep) {
    std::map<std::string, fs::file_time_type> newest;  // per run token
    std::vector<std::pair<std::string, fs::path>> files;
    for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
        const std::string name = e.path().filename().string();
        const std::size_t dash = name.find('-', 4);
        if (!name.starts_with("job-") || dash == std::string::npos || !e.is_regular_file() || e.is_symlink()) continue;
        const std::string token = name.substr(4, dash - 4);
        const fs::file_time_type time = e.last_write_time();
        newest[token] = std::max(newest[token], time);
        files.emplace_back(token, e.path());
    }
    std::vector<std::pair<fs::file_time_type, std::string>> runs;
    for (const auto& [token, time] : newest) runs.emplace_back(time, token);
    std::sort(runs.rbegin(), runs.rend());
    std::set<std::string> kept;
    for (std::size_t r = 0; r < std::min(keep, runs.size()); ++r) kept.insert(runs[r].second);
    for (const auto& [token, path] : files)
        if (!kept.contains(token)) fs::remove(path);
}

std::string randomToken() {
    std::random_device device;
    char text[33];
    std::snprintf(text, sizeof text, "%08x%08x%08x%08x", device(), device(), device(), device());
    return text;
}

// The check of slurm_executor.h, before the first job of a run: one small job on a compute node sees
// the tools, the plans' inputs and the first plan's results root.
void checkSlurmNodes(const std::vector<const Plan*>& plans, const RunOptions& options, FileHasher& hasher) {
    const fs::path folder = fs::absolute(plans.front()->resultsDir.parent_path()) / ".slurm-check";
    const std::string token = randomToken();
    NodeCheck check{token, {}, {}, folder / (token + ".report.json")};
    std::set<fs::path> tools, files;
    for (const fs::directory_entry& entry : fs::directory_iterator(options.toolDir))
        if (entry.is_regular_file() && entry.path().filename().string().starts_with("vri-"))
            tools.insert(fs::absolute(entry.path()));
    for (const Plan* plan : plans)
        for (const Step& step : plan->steps)
            for (const fs::path& input : step.inputs)
                if (fs::is_regular_file(input)) files.insert(fs::absolute(input));
    for (const fs::path& tool : tools) check.tools.emplace_back(tool, hasher.digest(tool));
    for (const fs::path& file : files) check.files.emplace_back(file, fs::file_size(file));
    fs::create_directories(folder);
    const fs::path checkFile = folder / (token + ".json"), script = folder / (token + ".sh"), out = folder / (token + ".out");
    // Only this check's files go, and its job's output stays when the check fails: the evidence.
    // Returns what could not be removed (a failure beside another error is not the one to report).
    const auto removeOwnFiles = [&](bool keepOutput) {
        std::string left;
        for (const fs::path& f : {checkFile, script, check.report, out}) {
            std::error_code ec;
            if ((f != out || !keepOutput) && !fs::remove(f, ec) && ec) left += " " + f.string() + " (" + ec.message() + ")";
        }
        std::error_code ec;
        if (!fs::is_symlink(folder, ec)) fs::remove(folder, ec);  // only when empty: another run's check may be there
        return left;
    };
    try {  // a full disk leaves neither half of the check behind
        writeNodeCheck(checkFile, check);
        writeJobScript(script);
    } catch (...) {
        removeOwnFiles(false);
        throw;
    }
    std::vector<std::string> arguments{"--job-name=vri:check", "--chdir=" + folder.string(), "--output=" + out.filename().string(),
                                       "--cpus-per-task=1", "--mem=256M", "--time=10"};
    arguments.insert(arguments.end(), options.slurm.sbatchArguments.begin(), options.slurm.sbatchArguments.end());
    arguments.insert(arguments.end(), {script.string(), fs::absolute(options.toolDir / "vri-run").string(),
                                       "--slurm-node-check", checkFile.string()});
    std::vector<std::string> problems;
    bool completed = true;  // unless squeue says otherwise (one that forgot it cannot)
    try {
        const std::string id = submitJob(arguments);
        PendingWatch pending("the Slurm check job " + id, options.slurm.maxPendingSeconds);
        SqueueOutage outage(options.slurm.maxOutageSeconds);
        bool ended = false;
        const auto unended = [&] { return ended ? std::vector<std::string>{} : std::vector<std::string>{id}; };
        cancelOnFailure(options.slurm.pollSeconds, unended, [&] {
            for (;;) {
                if (gSlurmInterrupt) throw Error("interrupted by " + signalName(gSlurmInterrupt));
                pause(options.slurm.pollSeconds);
                const std::optional<std::map<std::string, SlurmJob>> states = lookAtJobs({id}, outage);
                if (!states) continue;
                pending.update(*states, std::cerr, Clock::now());
                const auto found = states->find(id);
                if (found != states->end() && heldAfterFailedLaunch(found->second))
                    throw Error("the Slurm check job " + id +
                                " could not be started on its node (squeue's reason: " + kLaunchFailedReason +
                                "; sinfo -R says whether the node was drained for it; its output: " + out.string() +
                                ")");
                if (found == states->end() || isFinalJobState(found->second.state)) {
                    completed = found == states->end() || found->second.state == "COMPLETED";
                    ended = true;
                    return;
                }
            }
        });
        // A check that completed wrote its report, which a shared file system may show late.
        const auto start = Clock::now();
        while (completed && !fs::exists(check.report) && !gSlurmInterrupt &&
               std::chrono::duration<double>(Clock::now() - start).count() < kSharedFileDelaySeconds)
            pause(0.2);
        problems = readNodeCheckReport(check);
        if (!problems.empty())
            throw Error(problems.front() + " (the Slurm check job " + id +
                        "): tools, inputs and the results folder must be shared with the compute nodes at the same paths");
    } catch (...) {
        removeOwnFiles(true);
        throw;
    }
    if (const std::string left = removeOwnFiles(false); !left.empty())
        std::cerr << "vri-run: warning: the Slurm check's files could not be removed:" << left << '\n';
}

// One plan's part of a batch: its steps, its jobs and what became of them.
class SlurmRun {
public:
    SlurmRun(const Plan& plan, RunOptions options, FileHasher& hasher)
        : plan_(plan), options_(std::move(options)), ledger_(plan, options_, hasher),
          slurmDir_(plan.resultsDir / ".steps" / "slurm") {}

    // Settles the steps the cache vouches for and cuts the others into jobs; how many steps will run. Unless
    // --dry-run, first cancels the jobs an earlier vri-run on these results left in the queue.
    std::size_t prepare();
    // The jobs as submitMore() would submit them, without submitting or writing anything: a line per job
    // naming its steps, then its sbatch command, a job it waits for named "<job K>".
    void describe(std::ostream& out) const;
    const Plan& plan() const { return plan_; }
    // Submits the jobs in order, each after those it depends on, while fewer than `slots` of the batch's
    // jobs are in the queue (slots is what is left of --slurm-max-jobs; unlimited without it). A failure
    // leaves the jobs submitted so far in unendedIds() for the caller to cancel.
    void submitMore(std::size_t& slots);
    // Jobs not submitted yet (--slurm-max-jobs), an abandoned one not counted.
    std::size_t unsubmitted() const;
    std::vector<std::string> unendedIds() const;
    // Settles the steps of every job that squeue shows ended (or no longer knows).
    void update(const std::map<std::string, SlurmJob>& states);
    std::vector<StepOutcome> result() const { return ledger_.result(); }

private:
    struct Job {
        JobBundle bundle;
        std::string id;
        bool ended = false;
        std::set<std::size_t> dependsOn;  // indices of jobs
        // --slurm-retries: how often vri-run submitted it again (each attempt has files of its own), and the
        // factors its time and memory were raised by after TIMEOUT and OUT_OF_MEMORY.
        std::size_t retries = 0;
        double timeScale = 1.0, memoryScale = 1.0;
        int restarts = 0;  // how often Slurm requeued its current id, as last said
        std::string node;  // where squeue last placed its current id
        bool launchFailed = false;  // Slurm held its current id after its node could not start it: cancelled
        // The manifest's earlier attempts, vri-run's retries and Slurm's requeues in order ("job 12 NODE_FAIL
        // on n3", "job 12 requeued by Slurm (restart 1)").
        std::vector<std::string> history;
    };

    std::vector<std::size_t> stepsToRun();
    void submit(std::size_t j);
    // sbatch's arguments for job j, the jobs it waits for given by `dependencyIds`.
    std::vector<std::string> sbatchArguments(std::size_t j, const std::vector<std::string>& dependencyIds) const;
    void ended(std::size_t j, const SlurmJob& reported);
    // Job j ended as --slurm-retries retries: submitted again (first in submitMore), with the jobs after it
    // that Slurm would cancel for their dependency on it cancelled and submitted again after it.
    void retry(std::size_t j, const SlurmJob& state, const std::string& raised);
    // The jobs after job j that wait for it were submitted with a dependency on its id, which Slurm now
    // cancels them for (--kill-on-invalid-dep): they are cancelled here and submitted again after it.
    // Returns how many had been submitted.
    std::size_t submitAgainAfter(std::size_t j);
    // Job j's restart count rose: Slurm requeued it to run again under its id.
    void requeued(std::size_t j, const SlurmJob& state);
    // Slurm holds job j because its node could not launch it, until someone releases it (so that a broken node
    // does not take job after job): for vri-run that attempt failed. The job is cancelled (again at each look
    // while squeue still shows it held) and, once squeue shows it ended, ends LAUNCH_FAILED, which
    // --slurm-retries submits again as after NODE_FAIL.
    void launchFailed(std::size_t j);
    // What a retry of `job` after it ended in `state` raises ("" for nothing), or nullopt where it is not
    // retried: --slurm-retries used up, a state a retry does not mend, a TIMEOUT with no --time to raise.
    std::optional<std::string> retryRaises(const std::string& state, const Job& job) const;
    void abandonDependents(std::size_t j);
    // The jobs not ended that wait for job j, directly or through others, in order.
    std::vector<std::size_t> waitingFor(std::size_t j) const;
    // A run's job files carry a token of their own: a job of an earlier run still alive (one scancel
    // could not stop in time) finds its own files gone, and never reads this run's.
    // An attempt after the first has files of its own: the output an error message named stays.
    std::string jobStem(std::size_t j) const {
        const std::size_t attempt = jobs_[j].retries;
        return "job-" + token_ + "-" + std::to_string(j) + (attempt > 0 ? "-" + std::to_string(attempt + 1) : "");
    }
    // Step i's status file for its job's current attempt: a process of an earlier attempt still alive (a
    // node cut off, not dead) writes its own.
    fs::path statusPath(std::size_t i) const {
        fs::path status = ledger_.logPath(i);
        const std::size_t attempt = jobs_[jobOfStep_.at(i)].retries;
        return status.replace_extension(attempt > 0 ? ".status-" + std::to_string(attempt + 1) + ".json"
                                                    : ".status.json");
    }
    // Job j's resources as its attempt asks them: raised after TIMEOUT and OUT_OF_MEMORY (retry).
    JobResources resourcesOf(std::size_t j) const;

    const Plan& plan_;
    RunOptions options_;  // before ledger_, which keeps a reference
    StepLedger ledger_;
    fs::path slurmDir_;
    std::string token_ = randomToken();
    std::size_t stepCount_ = 0;
    std::vector<Job> jobs_;
    std::map<std::size_t, std::size_t> jobOfStep_;
    std::size_t next_ = 0;  // the first job not submitted yet
    std::set<std::size_t> again_;  // jobs to submit again (retry), before those from next_
};

std::vector<std::size_t> SlurmRun::stepsToRun() {
    std::vector<std::size_t> run;
    std::vector<bool> willRun(plan_.steps.size(), false);
    for (std::size_t i = 0; i < plan_.steps.size(); ++i) {
        bool upstreamRuns = false, upstreamUnavailable = false;
        for (std::size_t d : plan_.dependencies[i]) {
            upstreamRuns = upstreamRuns || willRun[d];
            upstreamUnavailable = upstreamUnavailable || (ledger_.settled(d) &&
                                                          ledger_.outcome(d).state == StepOutcome::State::Unavailable);
        }
        if (upstreamRuns && !upstreamUnavailable) {
            // Its inputs will be rewritten: nothing to compare a record with yet, so it runs. A step
            // whose own tool is not built is still settled (with its dependents) as locally.
            if (!fs::is_regular_file(ledger_.program(i))) {
                ledger_.needsRun(i);
                continue;
            }
        } else if (!ledger_.needsRun(i)) {
            continue;
        }
        willRun[i] = true;
        run.push_back(i);
    }
    return run;
}

void SlurmRun::submit(std::size_t j) {
    Job& job = jobs_[j];
    NodeSteps steps{fs::current_path(), {}, fs::absolute(ledger_.digestRecord())};
    for (std::size_t i : job.bundle.steps) {
        const std::vector<std::string> words = ledger_.prepare(i);
        fs::remove(statusPath(i));
        steps.steps.push_back({plan_.steps[i].id, fs::absolute(ledger_.program(i)), words,
                               fs::absolute(ledger_.logPath(i)), fs::absolute(statusPath(i))});
    }
    writeNodeSteps(slurmDir_ / (jobStem(j) + ".json"), steps);
    // A job it waits for that has ended, ended well (else this one was abandoned): only those still queued
    // are named, since Slurm forgets a job a while after it ends and then refuses a dependency on it.
    std::vector<std::string> dependencyIds;
    for (std::size_t d : job.dependsOn)
        if (!jobs_[d].ended) dependencyIds.push_back(jobs_[d].id);
    try {
        job.id = submitJob(sbatchArguments(j, dependencyIds));
        job.restarts = 0;
        job.node.clear();
        job.launchFailed = false;
    } catch (const Error& e) {
        // What vri-run asked for and where each comes from: a cluster's limits are met by changing those.
        const JobResources resources = resourcesOf(j);
        const std::string kind = slurmStepKind(plan_.steps[job.bundle.steps.front()]);
        throw Error(
            "step '" + plan_.steps[job.bundle.steps.front()].id + "': " + e.what() +
            " (the job asked --cpus-per-task=" + std::to_string(resources.cpus) +
            ": --slurm-cpus or the step's threads; --mem=" + std::to_string(resources.memoryMiB) +
            "M: from its inputs and pixels" + (job.retries == 0 ? "" : ", raised for its retry") +
            (resources.minutes ? "; --time=" + std::to_string(*resources.minutes) + ": from its last run's time" : "") +
            (options_.slurm.kinds.count(kind) ? "; or the site profile's kind " + kind : "") +
            "; a --slurm-arg=--mem=... or --slurm-arg=--time=... overrides them for every job)");
    }
}

std::vector<std::string> SlurmRun::sbatchArguments(std::size_t j, const std::vector<std::string>& dependencyIds) const {
    const Job& job = jobs_[j];
    const std::string stem = jobStem(j);
    const JobResources resources = resourcesOf(j);
    std::vector<std::string> arguments{"--job-name=" + jobName(plan_, job.bundle),
                                       "--chdir=" + slurmDir_.string(),
                                       "--output=" + stem + ".out",  // relative to --chdir: no '%' of a path is read as a pattern
                                       "--cpus-per-task=" + std::to_string(resources.cpus),
                                       "--mem=" + std::to_string(resources.memoryMiB) + "M"};
    if (resources.minutes) arguments.push_back("--time=" + std::to_string(*resources.minutes));
    if (!dependencyIds.empty()) {
        std::string after = "--dependency=afterok";
        for (const std::string& id : dependencyIds) after += ":" + id;
        arguments.insert(arguments.end(), {after, "--kill-on-invalid-dep=yes"});
    }
    arguments.insert(arguments.end(), options_.slurm.sbatchArguments.begin(), options_.slurm.sbatchArguments.end());
    arguments.insert(arguments.end(), {(slurmDir_ / "vri-job.sh").string(), fs::absolute(options_.toolDir / "vri-run").string(),
                                       "--slurm-node-steps", (slurmDir_ / (stem + ".json")).string()});
    return arguments;
}

void SlurmRun::describe(std::ostream& out) const {
    const std::string name = plan_.resultsDir.filename().string();
    for (std::size_t j = 0; j < jobs_.size(); ++j) {
        const Job& job = jobs_[j];
        out << "# " << name << ": job " << j + 1 << " of " << jobs_.size() << ":";
        for (std::size_t i : job.bundle.steps) out << " " << plan_.steps[i].id;
        out << (job.bundle.priced ? " (about " + secondsText(job.bundle.seconds) + ")" : " (not priced yet)") << "\n";
        std::vector<std::string> dependencyIds;
        for (std::size_t d : job.dependsOn) dependencyIds.push_back("<job " + std::to_string(d + 1) + ">");
        std::vector<std::string> words{"sbatch", "--parsable"};
        for (std::string& w : sbatchArguments(j, dependencyIds)) words.push_back(std::move(w));
        out << shellCommand(words) << "\n";
    }
}

std::vector<std::string> SlurmRun::unendedIds() const {
    std::vector<std::string> ids;
    for (const Job& job : jobs_)
        if (!job.ended && !job.id.empty()) ids.push_back(job.id);
    return ids;
}

std::vector<std::size_t> SlurmRun::waitingFor(std::size_t j) const {
    // Jobs depend only on jobs before them: one pass finds everything downstream of j.
    std::vector<bool> downstream(jobs_.size(), false);
    downstream[j] = true;
    std::vector<std::size_t> waiting;
    for (std::size_t k = j + 1; k < jobs_.size(); ++k) {
        for (std::size_t d : jobs_[k].dependsOn) downstream[k] = downstream[k] || downstream[d];
        if (downstream[k] && !jobs_[k].ended) waiting.push_back(k);
    }
    return waiting;
}

void SlurmRun::abandonDependents(std::size_t failed) {
    std::vector<std::string> cancel;
    for (std::size_t j : waitingFor(failed)) {
        Job& job = jobs_[j];
        // Slurm cancels it too (--kill-on-invalid-dep); saying so here does not depend on that. A job not
        // submitted yet (--slurm-max-jobs) never will be.
        if (!job.id.empty()) cancel.push_back(job.id);
        job.ended = true;
        again_.erase(j);
        for (std::size_t i : job.bundle.steps)
            if (!ledger_.settled(i)) ledger_.abandoned(i, "a step it depends on failed (Slurm job " + jobs_[failed].id + ")");
    }
    cancelJobs(cancel);
}

void SlurmRun::ended(std::size_t j, const SlurmJob& reported) {
    Job& job = jobs_[j];
    job.ended = true;
    // A job killed for its memory by jobacct_gather ends FAILED (JobLaunchFailure): its output says why.
    // Looked at now and again after the wait for late status files below (a shared file system may show
    // the output late too).
    SlurmJob state = reported;
    const auto killedForMemory = [&] {
        if (state.state != "FAILED") return;
        if (const std::optional<std::string> text = tryReadFileText(slurmDir_ / (jobStem(j) + ".out")))
            if (std::optional<std::string> kill = memoryLimitKill(*text)) {
                state.state = "OUT_OF_MEMORY";
                state.reason = "slurmstepd: " + *kill;
            }
    };
    killedForMemory();
    // A job that completed or failed wrote a status file for every step it ran (one squeue no longer
    // knows ended long ago); a shared file system may show them late. A job killed (cancelled, timed
    // out, preempted, out of memory) left none for the step it killed: nothing to wait for.
    const bool wroteStatuses = state.state == "COMPLETED" || state.state == "FAILED" || state.state == kForgotten;
    const auto start = Clock::now();
    // This job's status file for step i: one another job wrote (an earlier run's) is not this run's.
    const auto statusOf = [&](std::size_t i) {
        std::optional<NodeStepStatus> status = readNodeStepStatus(statusPath(i));
        return status && status->jobId == job.id ? status : std::nullopt;
    };
    bool failed = false;
    for (std::size_t i : job.bundle.steps) {
        if (ledger_.settled(i)) continue;
        std::optional<NodeStepStatus> status = failed ? std::nullopt : statusOf(i);
        while (!failed && !status && wroteStatuses && !gSlurmInterrupt &&
               std::chrono::duration<double>(Clock::now() - start).count() < kSharedFileDelaySeconds) {
            pause(0.2);
            status = statusOf(i);
        }
        if (!status && !failed) killedForMemory();
        const std::string where = "Slurm job " + job.id + " " + state.state + (state.node.empty() ? "" : " on " + state.node);
        if (failed) {
            ledger_.abandoned(i, "an earlier step of its " + where + " failed");
        } else if (status && status->exited && status->code == 0) {
            failed = !ledger_.succeeded(i, status->wallSeconds,
                                        // Slurm's name for the node, which sinfo and scontrol take; the host's own
                                        // where squeue has forgotten the job.
                                        {.executor = "slurm",
                                         .node = state.node.empty() ? status->node : state.node,
                                         .jobId = job.id,
                                         .jobState = state.state,
                                         .loadBefore = std::nullopt,
                                         .loadAfter = std::nullopt,
                                         .beside = {},
                                         .earlierAttempts = job.history,
                                         .peakRssMiB = peakRssMiB(status->peakRssKiB)});
        } else if (const std::optional<std::string> raised =
                       status && !status->exited ? retryRaises(state.state, job) : std::nullopt;
                   raised) {
            retry(j, state,
                  *raised);  // killed with its job (out of memory, out of time): the steps not settled run again
            return;
        } else if (status) {
            const ExitStatus exit{status->exited, status->code, status->signal};
            ledger_.failed(i, "failed (" + exit.describe() + ") in " + where, status->wallSeconds);
            failed = true;
        } else if (state.reason == "DependencyNeverSatisfied") {
            ledger_.abandoned(i, "a step it depends on failed (" + where + ")");
            failed = true;
        } else if (const std::optional<std::string> raised = retryRaises(state.state, job); raised) {
            retry(j, state, *raised);  // the steps not settled yet run again
            return;
        } else {
            const bool timeNotRaised = state.state == "TIMEOUT" && options_.slurm.retries > 0 &&
                                       job.retries < static_cast<std::size_t>(options_.slurm.retries);
            ledger_.failed(i,
                           "failed: " + where +
                               (state.reason.empty() || state.reason == "None" ? "" : " (" + state.reason + ")") +
                               (job.retries == 0 ? "" : " after " + std::to_string(job.retries + 1) + " attempts") +
                               (timeNotRaised ? "; not retried: vri-run asked no --time it could raise" : "") +
                               "; the job's output: " + (slurmDir_ / (jobStem(j) + ".out")).string(),
                           0);
            failed = true;
        }
    }
    if (failed) {
        abandonDependents(j);
    } else if (state.state != "COMPLETED" && state.state != kForgotten) {
        // Every step succeeded, yet Slurm ended the job otherwise (a scancel or a node failure that came
        // after its last step): the jobs waiting for it would never start, though nothing they need is missing.
        if (const std::size_t again = submitAgainAfter(j); again > 0)
            std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": Slurm job " << job.id << " ended "
                      << state.state << " after its steps had succeeded; the " << again
                      << (again == 1 ? " job" : " jobs") << " waiting for it submitted again\n";
    }
}

JobResources SlurmRun::resourcesOf(std::size_t j) const {
    const Job& job = jobs_[j];
    JobResources resources = jobResources(plan_, job.bundle, options_.slurm.cpus, options_.slurm.kinds);
    resources.memoryMiB = static_cast<long long>(std::ceil(static_cast<double>(resources.memoryMiB) * job.memoryScale));
    if (resources.minutes)
        resources.minutes = static_cast<long long>(std::ceil(static_cast<double>(*resources.minutes) * job.timeScale));
    return resources;
}

std::optional<std::string> SlurmRun::retryRaises(const std::string& state, const Job& job) const {
    if (gSlurmInterrupt || job.retries >= static_cast<std::size_t>(options_.slurm.retries)) return std::nullopt;
    if (state == "NODE_FAIL" || state == "PREEMPTED" || state == "BOOT_FAIL" || state == kLaunchFailed)
        return std::string();
    // A limit the user's sbatch options set wins over vri-run's (they come after it): raising it is out of reach.
    const auto userSets = [&](const std::string& option) {
        return std::ranges::any_of(options_.slurm.sbatchArguments,
                                   [&](const std::string& w) { return w.starts_with(option); });
    };
    if (state == "OUT_OF_MEMORY" && !userSets("--mem")) return "--mem x" + exactNumber(kRetryFactor);
    const bool timed = jobResources(plan_, job.bundle, options_.slurm.cpus, options_.slurm.kinds).minutes.has_value();
    if (state == "TIMEOUT" && timed && !userSets("--time") && !userSets("-t"))
        return "--time x" + exactNumber(kRetryFactor);
    return std::nullopt;
}

// Slurm ran job j again under its id (JobRequeue, or --requeue: its node failed, or it was preempted): its
// steps start over, which vri-run says, and the manifest lists as an attempt before.
void SlurmRun::requeued(std::size_t j, const SlurmJob& state) {
    Job& job = jobs_[j];
    for (int restart = job.restarts + 1; restart <= state.restarts; ++restart)
        job.history.push_back("job " + job.id + " requeued by Slurm (restart " + std::to_string(restart) + ")");
    job.restarts = state.restarts;
    std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": step '"
              << plan_.steps[job.bundle.steps.front()].id << "': Slurm requeued job " << job.id << " (restart "
              << state.restarts << "): it runs again under its id, now " << state.state
              << (state.reason.empty() || state.reason == "None" ? "" : " (" + state.reason + ")") << "\n";
}

void SlurmRun::launchFailed(std::size_t j) {
    Job& job = jobs_[j];
    if (!job.launchFailed)
        std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": step '"
                  << plan_.steps[job.bundle.steps.front()].id << "': Slurm job " << job.id
                  << " could not be started on " << (job.node.empty() ? "its node" : job.node)
                  << " (squeue's reason: " << kLaunchFailedReason
                  << "; sinfo -R says whether its node was drained for it); cancelling it\n";
    job.launchFailed = true;
    cancelJobs({job.id});  // one that fails is asked again at the next look
}

void SlurmRun::retry(std::size_t j, const SlurmJob& state, const std::string& raised) {
    Job& job = jobs_[j];
    const std::string attempt = "job " + job.id + " " + state.state + (state.node.empty() ? "" : " on " + state.node);
    ++job.retries;
    job.history.push_back(attempt);
    if (state.state == "TIMEOUT") job.timeScale *= kRetryFactor;
    if (state.state == "OUT_OF_MEMORY") job.memoryScale *= kRetryFactor;
    std::erase_if(job.bundle.steps, [&](std::size_t i) { return ledger_.settled(i); });
    submitAgainAfter(j);
    job.id.clear();
    job.ended = false;
    again_.insert(j);
    std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": step '"
              << plan_.steps[job.bundle.steps.front()].id << "': Slurm " << attempt << "; retrying (attempt "
              << job.retries + 1 << " of " << options_.slurm.retries + 1 << (raised.empty() ? "" : ", " + raised)
              << ")\n";
}

std::size_t SlurmRun::submitAgainAfter(std::size_t j) {
    std::vector<std::string> cancel;
    for (std::size_t k : waitingFor(j)) {
        if (jobs_[k].id.empty()) continue;  // not submitted yet: it names the new id when it is
        cancel.push_back(jobs_[k].id);
        jobs_[k].id.clear();
        again_.insert(k);
    }
    cancelJobs(cancel);  // a failure leaves them to Slurm, which cancels them for their dependency
    return cancel.size();
}

void SlurmRun::update(const std::map<std::string, SlurmJob>& states) {
    for (std::size_t j = 0; j < jobs_.size(); ++j) {
        if (jobs_[j].ended || jobs_[j].id.empty()) continue;
        Job& job = jobs_[j];
        const auto found = states.find(job.id);
        if (found != states.end() && !found->second.node.empty()) job.node = found->second.node;
        if (found != states.end() && heldAfterFailedLaunch(found->second)) {
            launchFailed(j);
            continue;
        }
        if (job.launchFailed) {
            if (found == states.end() || isFinalJobState(found->second.state))
                ended(j,
                      {job.id, kLaunchFailed, job.node, kLaunchFailedReason + ", cancelled by vri-run", job.restarts});
            continue;
        }
        if (found != states.end() && found->second.restarts > job.restarts) requeued(j, found->second);
        // A job squeue has forgotten ended long enough ago; its status files say how.
        if (found == states.end())
            ended(j, {job.id, kForgotten, "", "no longer known to squeue"});
        else if (isFinalJobState(found->second.state))
            ended(j, found->second);
    }
}

std::size_t SlurmRun::prepare() {
    // Jobs of an earlier run on these results that it could not cancel (killed with SIGKILL) would run its
    // steps beside this run's and could write an output after the cache was read or this run recorded it:
    // they go before anything else.
    const std::string name = plan_.resultsDir.filename().string();
    std::vector<std::string> orphans;
    if (!options_.slurm.dryRun) try {
            orphans = unendedJobsIn(slurmDir_);
        } catch (const Error& e) {  // a run that submits nothing needs no controller
            std::cerr << "vri-run: warning: " << name << ": " << e.what()
                      << ": the jobs of an earlier vri-run killed with SIGKILL were not looked for\n";
        }
    if (!orphans.empty()) {
        std::cerr << "vri-run: " << name << ": cancelling Slurm jobs " << jobList(orphans)
                  << " of an earlier vri-run on this results folder, still in the queue\n";
        if (const CancelOutcome outcome = cancelAndWait(orphans, options_.slurm.pollSeconds); !outcome.cancelled)
            throw Error(name + ": " + outcome.said + "; nothing was submitted beside them");
    }
    const std::vector<std::size_t> steps = stepsToRun();
    stepCount_ = steps.size();
    for (JobBundle& bundle : bundleSteps(plan_, steps, options_.prices, options_.slurm.bundleSeconds)) {
        for (std::size_t i : bundle.steps) jobOfStep_[i] = jobs_.size();
        jobs_.push_back({std::move(bundle), "", false, {}});
    }
    for (std::size_t j = 0; j < jobs_.size(); ++j)  // the jobs a job waits for: those writing its inputs
        for (std::size_t i : jobs_[j].bundle.steps)
            for (std::size_t d : plan_.dependencies[i])
                if (const auto found = jobOfStep_.find(d); found != jobOfStep_.end() && found->second != j)
                    jobs_[j].dependsOn.insert(found->second);
    return stepCount_;
}

void SlurmRun::submitMore(std::size_t& slots) {
    if ((next_ >= jobs_.size() && again_.empty()) || slots == 0) return;
    const bool first = next_ == 0;
    if (first) {
        requireOwnFolder(slurmDir_.parent_path());  // never a recursive delete through a link
        requireOwnFolder(slurmDir_);
        fs::create_directories(slurmDir_);
        pruneJobFiles(slurmDir_, kKeptRuns - 1);
        writeJobScript(slurmDir_ / "vri-job.sh");
    }
    std::vector<std::string> ids;
    while (!again_.empty() && slots > 0) {  // retried jobs and those waiting for them, in order
        const std::size_t j = *again_.begin();
        again_.erase(again_.begin());
        if (jobs_[j].ended) continue;  // abandoned meanwhile
        if (gSlurmInterrupt) throw Error("interrupted by " + signalName(gSlurmInterrupt) + " while submitting");
        try {
            submit(j);
        } catch (const Error& e) {  // raised past what the cluster takes: this job fails, the run goes on
            jobs_[j].ended = true;
            for (std::size_t i : jobs_[j].bundle.steps)
                if (!ledger_.settled(i)) ledger_.failed(i, std::string("could not be submitted again: ") + e.what(), 0);
            abandonDependents(j);
            continue;
        }
        ids.push_back(jobs_[j].id);
        --slots;
    }
    for (; next_ < jobs_.size() && slots > 0; ++next_) {
        if (jobs_[next_].ended) continue;  // abandoned before it was submitted
        if (gSlurmInterrupt) throw Error("interrupted by " + signalName(gSlurmInterrupt) + " while submitting");
        submit(next_);
        ids.push_back(jobs_[next_].id);
        --slots;
    }
    if (ids.empty()) return;
    const std::string name = plan_.resultsDir.filename().string();
    if (first)
        std::cerr << "vri-run: " << name << ": " << stepCount_ << " steps in Slurm jobs " << jobList(ids)
                  << (unsubmitted() > 0 ? ", " + std::to_string(unsubmitted()) + " more as these end (--slurm-max-jobs)"
                                        : "")
                  << "\n";
    else if (!options_.quiet)
        std::cerr << "vri-run: " << name << ": submitted Slurm jobs " << jobList(ids) << ", " << unsubmitted()
                  << " to come\n";
}

std::size_t SlurmRun::unsubmitted() const {
    std::size_t n = 0;
    for (std::size_t j : again_) n += !jobs_[j].ended;
    for (std::size_t j = next_; j < jobs_.size(); ++j) n += !jobs_[j].ended;
    return n;
}

}  // namespace slurm_detail

struct SlurmBatch::Impl {
    const RunOptions& options;
    FileHasher& hasher;
    slurm_detail::InterruptGuard guard;
    std::vector<std::unique_ptr<slurm_detail::SlurmRun>> runs;

    std::vector<std::string> unendedIds() const {
        std::vector<std::string> ids;
        for (const auto& run : runs)
            for (std::string& id : run->unendedIds()) ids.push_back(std::move(id));
        return ids;
    }
    // Submits what --slurm-max-jobs lets in beside the jobs in the queue, plan by plan in order.
    void submitMore() {
        const std::size_t cap = options.slurm.maxJobs;
        std::size_t queued = unendedIds().size();
        std::size_t slots = cap == 0 ? std::numeric_limits<std::size_t>::max() : cap > queued ? cap - queued : 0;
        for (const auto& r : runs) r->submitMore(slots);
    }
    bool anyUnsubmitted() const {
        return std::ranges::any_of(runs, [](const auto& r) { return r->unsubmitted() > 0; });
    }
};

SlurmBatch::SlurmBatch(const RunOptions& options, FileHasher& hasher) : impl_(new Impl{options, hasher, {}, {}}) {}
SlurmBatch::~SlurmBatch() = default;

std::size_t SlurmBatch::add(const Plan& plan, std::vector<std::optional<double>> prices) {
    RunOptions options = impl_->options;
    options.prices = std::move(prices);
    impl_->runs.push_back(std::make_unique<slurm_detail::SlurmRun>(plan, std::move(options), impl_->hasher));
    return impl_->runs.back()->prepare();
}

void SlurmBatch::describe(std::ostream& out) {
    for (const auto& r : impl_->runs) r->describe(out);
}

void SlurmBatch::checkNodes() {
    if (*impl_->options.slurm.nodesChecked || impl_->runs.empty()) return;
    std::vector<const Plan*> plans;
    for (const auto& r : impl_->runs) plans.push_back(&r->plan());
    slurm_detail::checkSlurmNodes(plans, impl_->options, impl_->hasher);
    *impl_->options.slurm.nodesChecked = true;
}

void SlurmBatch::run() {
    const double poll = impl_->options.slurm.pollSeconds;
    // Whatever stops the submission or the watch (an interrupt, squeue failing past --slurm-max-outage, a
    // record that cannot be written), no job of this batch is left behind, and the message says so.
    slurm_detail::cancelOnFailure(
        poll, [&] { return impl_->unendedIds(); },
        [&] {
            impl_->submitMore();
            PendingWatch pending("Slurm jobs", impl_->options.slurm.maxPendingSeconds);
            slurm_detail::SqueueOutage outage(impl_->options.slurm.maxOutageSeconds);
            PollInterval interval(poll);
            std::map<std::string, std::string> seen;  // job id -> state at the last look
            for (std::vector<std::string> ids = impl_->unendedIds(); !ids.empty() || impl_->anyUnsubmitted();
                 ids = impl_->unendedIds()) {
                if (gSlurmInterrupt) throw Error("interrupted by " + slurm_detail::signalName(gSlurmInterrupt));
                slurm_detail::pause(interval.seconds());
                const std::optional<std::map<std::string, SlurmJob>> states = slurm_detail::lookAtJobs(ids, outage);
                if (!states) continue;
                std::map<std::string, std::string> now;
                for (const auto& [id, job] : *states) now[id] = job.state;
                interval.looked(now != seen);
                seen = std::move(now);
                for (const auto& r : impl_->runs) r->update(*states);
                impl_->submitMore();
                pending.update(*states, std::cerr, slurm_detail::Clock::now());
            }
        });
}

std::vector<StepOutcome> SlurmBatch::result(std::size_t k) const { return impl_->runs.at(k)->result(); }

std::vector<StepOutcome> runPlanOnSlurm(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    SlurmBatch batch(options, hasher);
    if (batch.add(plan, options.prices) > 0) {
        batch.checkNodes();
        batch.run();
    }
    return batch.result(0);
}

}  // namespace vri
