// The steps of a run: cache decisions, records of steps that ran, progress and the first failure.
#include "libvri/experiment/step_ledger.h"

#include <cstdio>
#include <iostream>
#include <set>
#include <sstream>

#include "libvri/io/provenance.h"
#include "libvri/render/render_job.h"  // timingLoadOf
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"
#include "libvri/util/input_digest.h"
#include "libvri/util/json_file.h"
#include "libvri/util/own_folder.h"
#include "libvri/util/printable.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

std::string secondsDetail(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f s", seconds);
    return text;
}

}  // namespace

StepLedger::StepLedger(const Plan& plan, const RunOptions& options, FileHasher& hasher)
    : plan_(plan), options_(options), hasher_(hasher), outcomes_(plan.steps.size()),
      settled_(plan.steps.size(), false), keys_(stepKeys(plan, options.toolDir, hasher)),
      progress_(plan, options.prices, options.executor == Executor::Local ? options.jobs : 1,
                StepProgress::styleFor(options.quiet)) {
    for (const Step& step : plan.steps) programs_.push_back(options.toolDir / step.tool);
    requireOwnFolder(plan.resultsDir / ".steps");
    digestRecord_ = plan.resultsDir / ".steps" / "input-digests.json";
}

void StepLedger::settle(std::size_t i, StepOutcome::State state, const std::string& how, const std::string& detail) {
    settled_[i] = true;
    outcomes_[i].state = state;
    progress_.settled(i, how, detail);
}

void StepLedger::settleUnavailable(std::size_t i) { settle(i, StepOutcome::State::Unavailable, "skipped", "not built"); }

bool StepLedger::needsRun(std::size_t i) {
    for (std::size_t d : plan_.dependencies[i])
        if (outcomes_[d].state == StepOutcome::State::Unavailable) {
            settleUnavailable(i);
            return false;
        }
    const Step& step = plan_.steps[i];
    if (!fs::is_regular_file(programs_[i])) {
        if (missingTools_.insert(step.tool).second)
            std::cerr << "vri-run: warning: " << programs_[i].string() << " is not built; its steps are skipped\n";
        settleUnavailable(i);
        return false;
    }
    if (!options_.force) {
        if (auto last = readRecord(recordPath(plan_, step)); last && recordIsCurrent(*last, keys_[i], plan_, step, hasher_)) {
            outcomes_[i].record = *last;
            settle(i, StepOutcome::State::Cached, "cached", secondsDetail(last->wallSeconds) + " when it ran");
            return false;
        }
    }
    return true;
}

fs::path StepLedger::logPath(std::size_t i) const {
    fs::path log = recordPath(plan_, plan_.steps[i]);
    return log.replace_extension(".log");
}

std::vector<std::string> StepLedger::prepare(std::size_t i) {
    if (!digestRecordWritten_) {  // before the first step runs (a dry run writes nothing)
        // The source files the keys digested (a step's outputs are another's inputs, digested once it ran).
        std::vector<StampedDigest> sources;
        std::set<fs::path> produced, listed;
        for (const Step& step : plan_.steps) produced.insert(step.outputs.begin(), step.outputs.end());
        for (const Step& step : plan_.steps)
            for (const fs::path& input : step.inputs)
                if (!produced.contains(input) && listed.insert(input).second) {
                    const std::string& sha512 = hasher_.digest(input);
                    if (const std::optional<FileStamp> stamp = hasher_.stamp(input))
                        sources.push_back({input, sha512, *stamp});
                }
        writeDigestRecord(digestRecord_, sources);
        digestRecordWritten_ = true;
    }
    const fs::path record = recordPath(plan_, plan_.steps[i]);
    // A link in their place (to anywhere) is removed, never written through: the step's log is opened for
    // writing and truncated as the step starts.
    fs::remove(record);
    fs::remove(logPath(i));
    fs::create_directories(record.parent_path());
    std::vector<std::string> words = commandWords(plan_, plan_.steps[i], options_.toolDir);
    outcomes_[i].record.command = shellCommand(words);
    return words;
}

bool StepLedger::succeeded(std::size_t i, double wallSeconds, const StepExecution& execution) {
    const Step& step = plan_.steps[i];
    StepRecord& record = outcomes_[i].record;
    record.wallSeconds = wallSeconds;
    record.execution = execution;
    for (const fs::path& out : step.outputs) hasher_.forget(out);
    record.key = keys_[i];
    record.inputs = digestFiles(plan_, step.inputs, hasher_);
    record.outputs = digestFiles(plan_, step.outputs, hasher_);
    record.ranUtc = utcTimestamp();
    for (const FileDigest& out : record.outputs)
        if (out.sha512 == "missing") {
            failed(i, "succeeded but did not write " + out.path, wallSeconds);
            return false;
        }
    // Its outputs are sound whatever else failed: a rerun need not make them again.
    writeRecord(recordPath(plan_, step), record);
    // The tool's warnings (timed under load, more threads than cores, ...) reach the console, the rest of its
    // output goes with the log.
    if (const std::optional<std::string> log = tryReadFileText(logPath(i))) {
        std::istringstream lines(*log);
        for (std::string line; std::getline(lines, line);)
            if (line.find(": warning: ") != std::string::npos)
                progress_.warning(i, printable(line.substr(0, 400)));
    }
    fs::remove(logPath(i));
    if (step.kind == "render") warnIfTimedUnderLoad(i);
    std::string detail = secondsDetail(wallSeconds);
    if (!execution.jobId.empty()) detail += ", job " + execution.jobId + " on " + execution.node;
    settle(i, StepOutcome::State::Ran, "ran", detail);
    return true;
}

void StepLedger::warnIfTimedUnderLoad(std::size_t i) {
    for (const fs::path& out : plan_.steps[i].outputs) {
        if (out.extension() != ".json") continue;
        try {
            const std::optional<TimingLoad> load = timingLoadOf(readJsonFile(out));
            if (!load || !load->overloaded()) continue;
            char text[160];
            std::snprintf(text, sizeof text,
                          "warning: timed while other processes used %.1f cores beside its %d threads on %d cores: "
                          "its seconds are inflated",
                          load->otherCores, load->threads, load->cores);
            progress_.warning(i, text);
        } catch (const std::exception&) {
            // Not a stats record: nothing to say of its timing.
        }
    }
}

void StepLedger::failed(std::size_t i, const std::string& why, double wallSeconds) {
    outcomes_[i].record.wallSeconds = wallSeconds;
    if (failure_.empty()) {
        // The command on a line of its own (a path in it may hold a newline: escaped), then the tool's own output.
        std::string log = tryReadFileText(logPath(i)).value_or("");
        while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
        failure_ = "step '" + plan_.steps[i].id + "' " + why + ":\n  " + printable(outcomes_[i].record.command) +
                   (log.empty() ? "" : "\n" + log);
    }
    settled_[i] = true;
    // "failed (exit status 3)" reads "failed vri-x id (exit status 3)" in the progress line.
    std::string detail = why;
    if (detail.starts_with("failed (") && detail.ends_with(")")) detail = detail.substr(8, detail.size() - 9);
    else if (detail.starts_with("failed: ")) detail = detail.substr(8);
    progress_.settled(i, "failed", detail);
}

void StepLedger::abandoned(std::size_t i, const std::string& why) {
    if (failure_.empty()) failure_ = "step '" + plan_.steps[i].id + "' did not run: " + why;
    settled_[i] = true;
    progress_.settled(i, "did not run", why);
}

std::vector<StepOutcome> StepLedger::result() const {
    if (!failure_.empty()) throw DetailedError(failure_);
    return outcomes_;
}

}  // namespace vri
