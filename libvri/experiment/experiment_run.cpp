// The scheduler of vri-run: processes for steps, the step cache, progress and failures.
#include "libvri/experiment/experiment_run.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>

#include "libvri/io/provenance.h"
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"
#include "libvri/util/process.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

class Scheduler {
public:
    Scheduler(const Plan& plan, const RunOptions& options, FileHasher& hasher)
        : plan_(plan), options_(options), hasher_(hasher), outcomes_(plan.steps.size()),
          state_(plan.steps.size(), Waiting), keys_(stepKeys(plan, options.toolDir, hasher)),
          showProgress_(::isatty(STDERR_FILENO)) {}

    std::vector<StepOutcome> run();

private:
    enum State { Waiting, Running, Finished };
    struct Child {
        std::size_t step;
        Clock::time_point start;
        fs::path log;
    };

    bool startReady();  // starts or settles every step whose dependencies are finished; false when nothing changed
    void settle(std::size_t i, StepOutcome::State how);
    void finish(pid_t pid, const ExitStatus& status);
    void report(std::size_t i, const std::string& how);

    const Plan& plan_;
    const RunOptions& options_;
    FileHasher& hasher_;
    std::vector<StepOutcome> outcomes_;
    std::vector<State> state_;
    std::vector<std::string> keys_;
    bool showProgress_;
    std::map<pid_t, Child> running_;
    std::size_t finished_ = 0;
    std::set<std::string> missingTools_;
    std::string failure_;  // the first failed step's command and output
};

void Scheduler::report(std::size_t i, const std::string& how) {
    ++finished_;
    if (!showProgress_) return;
    std::fprintf(stderr, "[%zu/%zu] %s %s (%s)\n", finished_, plan_.steps.size(), plan_.steps[i].tool.c_str(),
                 plan_.steps[i].id.c_str(), how.c_str());
}

void Scheduler::settle(std::size_t i, StepOutcome::State how) {
    state_[i] = Finished;
    outcomes_[i].state = how;
    report(i, how == StepOutcome::State::Cached ? "cached" : "not built, skipped");
}

bool Scheduler::startReady() {
    bool changed = false;
    for (std::size_t i = 0; i < plan_.steps.size() && failure_.empty(); ++i) {
        if (state_[i] != Waiting || static_cast<int>(running_.size()) >= options_.jobs) continue;
        bool ready = true, upstreamUnavailable = false;
        for (std::size_t d : plan_.dependencies[i]) {
            ready = ready && state_[d] == Finished;
            upstreamUnavailable = upstreamUnavailable || outcomes_[d].state == StepOutcome::State::Unavailable;
        }
        if (!ready) continue;
        changed = true;
        const Step& step = plan_.steps[i];
        const fs::path tool = options_.toolDir / step.tool;
        if (upstreamUnavailable || !fs::is_regular_file(tool)) {
            if (!upstreamUnavailable && missingTools_.insert(step.tool).second)
                std::cerr << "vri-run: warning: " << tool.string() << " is not built; its steps are skipped\n";
            settle(i, StepOutcome::State::Unavailable);
            continue;
        }
        const fs::path record = recordPath(plan_, step);
        if (!options_.force) {
            if (auto last = readRecord(record); last && recordIsCurrent(*last, keys_[i], plan_, step, hasher_)) {
                outcomes_[i].record = *last;
                settle(i, StepOutcome::State::Cached);
                continue;
            }
        }
        // The old record goes first: if this run is interrupted, nothing vouches for half-made outputs.
        fs::remove(record);
        fs::create_directories(record.parent_path());
        const std::vector<std::string> words = commandWords(plan_, step, options_.toolDir);
        outcomes_[i].record.command = shellCommand(words);
        fs::path log = record;
        log.replace_extension(".log");
        running_[startProcess(tool, words, {.in = "/dev/null", .out = log, .err = {}, .errToOut = true})] =
            Child{i, Clock::now(), log};
        state_[i] = Running;
    }
    return changed;
}

void Scheduler::finish(pid_t pid, const ExitStatus& status) {
    const auto found = running_.find(pid);
    if (found == running_.end()) return;
    const Child child = found->second;
    running_.erase(found);
    const std::size_t i = child.step;
    const Step& step = plan_.steps[i];
    StepRecord& record = outcomes_[i].record;
    record.wallSeconds = std::chrono::duration<double>(Clock::now() - child.start).count();
    if (!status.ok()) {
        if (failure_.empty())
            failure_ = "step '" + step.id + "' failed (" + status.describe() + "):\n  " + record.command + "\n" +
                       tryReadFileText(child.log).value_or("");
        state_[i] = Finished;
        return;
    }
    for (const fs::path& out : step.outputs) hasher_.forget(out);
    record.key = keys_[i];
    record.inputs = digestFiles(plan_, step.inputs, hasher_);
    record.outputs = digestFiles(plan_, step.outputs, hasher_);
    record.ranUtc = utcTimestamp();
    for (const FileDigest& out : record.outputs)
        if (out.sha512 == "missing" && failure_.empty())
            failure_ = "step '" + step.id + "' succeeded but did not write " + out.path + ":\n  " + record.command + "\n" +
                       tryReadFileText(child.log).value_or("");
    if (failure_.empty()) writeRecord(recordPath(plan_, step), record);
    fs::remove(child.log);
    state_[i] = Finished;
    outcomes_[i].state = StepOutcome::State::Ran;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f s", record.wallSeconds);
    report(i, seconds);
}

std::vector<StepOutcome> Scheduler::run() {
    for (;;) {
        while (startReady()) {
        }
        if (running_.empty()) break;
        const auto [pid, status] = waitAnyProcess();
        finish(pid, status);
    }
    if (!failure_.empty()) throw Error(failure_);
    return outcomes_;
}

}  // namespace

std::vector<StepOutcome> runPlan(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    if (options.jobs < 1) throw Error("--jobs: expected at least 1, got " + std::to_string(options.jobs));
    return Scheduler(plan, options, hasher).run();
}

}  // namespace vri
