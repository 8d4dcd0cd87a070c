// sbatch, squeue and scancel as argument vectors, and what they print read back.
#include "libvri/experiment/slurm_commands.h"

#include <algorithm>
#include <set>
#include <sstream>

#include <unistd.h>

#include "libvri/util/error.h"
#include "libvri/util/printable.h"
#include "libvri/util/process.h"

namespace vri {

namespace {

// `s` without its leading and trailing spaces: squeue pads its fields.
std::string trimmedField(std::string s) {
    s.erase(0, s.find_first_not_of(' '));
    s.erase(s.find_last_not_of(' ') + 1);
    return s;
}

// squeue's fields, '|' after each (no field holds one): the format squeueArguments asks for.
constexpr const char* kSqueueFormat = "JobID:|,State:|,NodeList:|,Reason:|,RestartCnt:|";
constexpr std::size_t kSqueueFields = 5;

std::filesystem::path slurmProgram(const std::string& name) {
    const auto program = findProgram(name);
    if (!program)
        throw Error(name + ": not found in PATH (--executor slurm needs Slurm's client commands: sbatch, squeue, scancel)");
    return *program;
}

// The line of `output` that says why a command failed: its first "error:" line, else its first line.
std::string firstErrorLine(const std::string& output) {
    std::istringstream lines(output);
    std::string line, first;
    while (std::getline(lines, line)) {
        if (first.empty()) first = line;
        if (line.find("error:") != std::string::npos) return line;
    }
    return first.empty() ? "no output" : first;
}

}  // namespace

bool isFinalJobState(const std::string& state) {
    static const std::set<std::string> final{"COMPLETED", "FAILED",        "TIMEOUT",   "CANCELLED", "PREEMPTED",
                                             "NODE_FAIL", "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE",  "REVOKED",
                                             "SPECIAL_EXIT"};
    static const std::set<std::string> going{"PENDING",      "RUNNING",  "SUSPENDED",    "COMPLETING",
                                             "CONFIGURING",  "REQUEUED", "REQUEUE_FED",  "REQUEUE_HOLD",
                                             "RESIZING",     "SIGNALING", "STAGE_OUT",   "STOPPED",
                                             "RESV_DEL_HOLD"};
    if (final.contains(state)) return true;
    if (going.contains(state)) return false;
    throw Error("squeue says a job is in state '" + printableShort(state, 40) +
                "', which vri-run does not know (neither one a job leaves nor one it ends in)");
}

std::optional<std::string> memoryLimitKill(const std::string& text) {
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        const std::size_t step = line.find("StepId=");
        const std::size_t what = line.find(" exceeded memory limit (");
        if (step == std::string::npos || what == std::string::npos || what < step) continue;
        const std::size_t end = line.find(')', what);
        if (end == std::string::npos) continue;
        return printable(line.substr(step, end + 1 - step));
    }
    return std::nullopt;
}

std::vector<std::string> squeueArguments(const std::vector<std::string>& jobIds) {
    std::string list;
    for (const std::string& id : jobIds) list += (list.empty() ? "" : ",") + id;
    // --all: jobs in hidden partitions too; explicit options win over a user's SQUEUE_* variables.
    return {"squeue", "--noheader", "--all", "--states=all", "--jobs=" + list, "--Format=" + std::string(kSqueueFormat)};
}

std::map<std::string, SlurmJob> parseSqueue(const std::string& output) {
    std::map<std::string, SlurmJob> jobs;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::vector<std::string> fields;
        std::size_t start = 0;
        for (std::size_t bar; (bar = line.find('|', start)) != std::string::npos; start = bar + 1)
            fields.push_back(line.substr(start, bar - start));
        for (std::string& f : fields) f = trimmedField(f);
        if (fields.size() != kSqueueFields || fields[0].empty() || fields[1].empty())
            throw Error("squeue printed a line vri-run cannot read: " + printableShort(line));
        // Slurm counts restarts in 16 bits; more digits are no count of its.
        const std::string& restarts = fields[4];
        if (restarts.empty() || restarts.size() > 5 ||
            !std::all_of(restarts.begin(), restarts.end(), [](char c) { return c >= '0' && c <= '9'; }))
            throw Error("squeue printed a line vri-run cannot read (restart count '" + printableShort(restarts, 40) +
                        "'): " + printableShort(line));
        // The state is its first word, should a Slurm version say more ("CANCELLED by 0", as sacct does).
        jobs[fields[0]] = {fields[0], fields[1].substr(0, fields[1].find(' ')), fields[2], fields[3],
                           std::stoi(restarts)};
    }
    return jobs;
}

std::string parseSbatchJobId(const std::string& output) {
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        const std::string id = line.substr(0, line.find(';'));
        if (id.empty() || !std::all_of(id.begin(), id.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
        // Slurm's ids are 32-bit; a longer run of digits is not one (and would not fit where ids are counted).
        if (id.size() > 10 || std::stoull(id) > 0xFFFFFFFFull)
            throw Error("sbatch printed a job id vri-run cannot use: " + printableShort(id, 40) +
                        " (Slurm's are below 2^32)");
        return id;
    }
    throw Error("sbatch printed no job id: " + printableShort(firstErrorLine(output)));
}

namespace {

// The sbatch options a site or user may add: what the jobs ask for (account, queue, time, resources,
// placement, notices), never where their files go, their order or how vri-run reads them.
enum class SiteValue { Required, None, Optional };
struct SiteOption {
    std::string_view name;
    SiteValue value;
};
constexpr SiteOption kSiteOptions[] = {
    {"--account", SiteValue::Required},       {"--qos", SiteValue::Required},
    {"--partition", SiteValue::Required},     {"--reservation", SiteValue::Required},
    {"--wckey", SiteValue::Required},         {"--time", SiteValue::Required},
    {"--time-min", SiteValue::Required},      {"--begin", SiteValue::Required},
    {"--deadline", SiteValue::Required},      {"--nice", SiteValue::Required},
    {"--priority", SiteValue::Required},      {"--mem", SiteValue::Required},
    {"--mem-per-cpu", SiteValue::Required},   {"--cpus-per-task", SiteValue::Required},
    {"--tmp", SiteValue::Required},           {"--gres", SiteValue::Required},
    {"--gpus", SiteValue::Required},          {"--gpus-per-node", SiteValue::Required},
    {"--gpus-per-task", SiteValue::Required}, {"--licenses", SiteValue::Required},
    {"--constraint", SiteValue::Required},    {"--prefer", SiteValue::Required},
    {"--nodelist", SiteValue::Required},      {"--exclude", SiteValue::Required},
    {"--hint", SiteValue::Required},          {"--threads-per-core", SiteValue::Required},
    {"--comment", SiteValue::Required},       {"--mail-type", SiteValue::Required},
    {"--mail-user", SiteValue::Required},     {"--signal", SiteValue::Required},
    {"--exclusive", SiteValue::Optional},     {"--requeue", SiteValue::None},
    {"--no-requeue", SiteValue::None},        {"--oversubscribe", SiteValue::None},
    {"--contiguous", SiteValue::None}};

// Those vri-run sets itself, and why: named in the refusal of one of them.
constexpr std::pair<std::string_view, std::string_view> kOwnedOptions[] = {
    {"--dependency", "the jobs' order"}, {"--kill-on-invalid-dep", "the jobs' order"},
    {"--array", "one job per bundle"},   {"--clusters", "the cluster vri-run watches"},
    {"--chdir", "the jobs' files"},      {"--output", "the jobs' files"},
    {"--error", "the jobs' files"},      {"--parsable", "reading the job id"},
    {"--wait", "watching the jobs"},     {"--wrap", "the job script"},
    {"--job-name", "the jobs' names"}};

}  // namespace

void checkSiteSbatchOption(const std::string& option, const std::string& source) {
    const std::string quoted = "'" + printableShort(option) + "'";
    if (option.size() < 2 || option[0] != '-')
        throw Error(source + ": " + quoted + " is not an sbatch option (expected one word such as --qos=long)");
    if (option[1] != '-')
        throw Error(source + ": " + quoted + ": short options are refused (sbatch reads a bundle such as -vo<path> as "
                    "-v -o <path>); use the long form, such as --partition=short");
    const std::size_t equals = option.find('=');
    const std::string name = option.substr(0, equals);
    // sbatch, through getopt_long, takes any unambiguous beginning of a long option ("--depend="): one of
    // vri-run's own is named as such, and only whole names are passed on.
    for (const auto& [owner, why] : kOwnedOptions)
        if (name.size() > 2 && owner.starts_with(name))
            throw Error(source + ": " + quoted + ": vri-run sets " + std::string(owner) + " itself (" + std::string(why) + ")");
    for (const SiteOption& allowed : kSiteOptions) {
        if (allowed.name != name) continue;
        if (allowed.value == SiteValue::Required && (equals == std::string::npos || equals + 1 == option.size()))
            throw Error(source + ": " + quoted + ": needs its value in the same word (" + name + "=VALUE)");
        if (allowed.value == SiteValue::None && equals != std::string::npos)
            throw Error(source + ": " + quoted + ": " + name + " takes no value");
        if (equals != std::string::npos && option.find_first_of("\n\r", equals) != std::string::npos)
            throw Error(source + ": " + quoted + ": a value holds a line break");
        return;
    }
    std::string list;
    for (const SiteOption& allowed : kSiteOptions) list += (list.empty() ? "" : ", ") + std::string(allowed.name);
    throw Error(source + ": " + quoted + " is not among the sbatch options vri-run passes on (" + list + ")");
}

volatile std::sig_atomic_t gSlurmInterrupt = 0;

namespace {

const CaptureLimits kClientLimits{kSlurmClientSeconds, kSlurmClientBytes, &gSlurmInterrupt};
// What a stopped vri-run does last (cancel its jobs, wait for them): within the limits, but not stopped by the signal.
const CaptureLimits kLastClientLimits{kSlurmClientSeconds, kSlurmClientBytes, nullptr};

}  // namespace

std::string submitJob(const std::vector<std::string>& arguments) {
    std::vector<std::string> words{"sbatch", "--parsable"};
    words.insert(words.end(), arguments.begin(), arguments.end());
    const auto [status, output] =
        captureProcess(slurmProgram("sbatch"), words, {.in = "/dev/null", .out = {}, .err = {}, .errToOut = true},
                       kClientLimits);
    if (!status.ok()) throw Error("sbatch refused the job (" + status.describe() + "): " + printableShort(firstErrorLine(output)));
    return parseSbatchJobId(output);
}

std::map<std::string, SlurmJob> queryJobs(const std::vector<std::string>& jobIds, bool interruptible) {
    if (jobIds.empty()) return {};
    const CaptureLimits& limits = interruptible ? kClientLimits : kLastClientLimits;
    const std::filesystem::path squeue = slurmProgram("squeue");
    const std::vector<std::string> words = squeueArguments(jobIds);
    // Its warnings on stderr are not job lines: only stdout is read.
    const auto [status, output] =
        captureProcess(squeue, words, {.in = "/dev/null", .out = {}, .err = "/dev/null", .errToOut = false}, limits);
    if (status.ok()) return parseSqueue(output);
    // squeue lists the ids it knows and skips the others, but fails when it knows none of them; asked
    // again with its stderr, its message tells that from a controller that does not answer.
    const auto [again, said] =
        captureProcess(squeue, words, {.in = "/dev/null", .out = {}, .err = {}, .errToOut = true}, limits);
    if (again.ok()) return parseSqueue(said);
    if (said.find("Invalid job id") != std::string::npos) return {};
    throw Error("squeue failed (" + again.describe() + "): " + printableShort(firstErrorLine(said)));
}

std::vector<std::string> parseUnendedIn(const std::string& output, const std::string& workDir) {
    std::vector<std::string> ids;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        const std::size_t idEnd = line.find('|'), stateEnd = idEnd == std::string::npos ? idEnd : line.find('|', idEnd + 1);
        if (stateEnd == std::string::npos) continue;  // not a job line
        const std::string id = trimmedField(line.substr(0, idEnd));
        const std::string state = trimmedField(line.substr(idEnd + 1, stateEnd - idEnd - 1));
        std::string dir = line.substr(stateEnd + 1);
        dir.erase(dir.find_last_not_of(' ') + 1);  // the field's padding (a path ending in a space is not matched)
        if (id.empty() || dir != workDir) continue;
        if (!isFinalJobState(state.substr(0, state.find(' ')))) ids.push_back(id);
    }
    return ids;
}

std::vector<std::string> unendedJobsIn(const std::filesystem::path& workDir) {
    // --user by number: --me needs Slurm 20.11.
    const std::vector<std::string> words{"squeue", "--noheader", "--user=" + std::to_string(::getuid()), "--all", "--states=all",
                                         "--Format=JobID:|,State:|,WorkDir:"};
    const auto [status, output] = captureProcess(slurmProgram("squeue"), words,
                                                 {.in = "/dev/null", .out = {}, .err = "/dev/null", .errToOut = false},
                                                 kClientLimits);
    if (!status.ok()) throw Error("squeue failed (" + status.describe() + ") listing this user's jobs");
    return parseUnendedIn(output, workDir.string());
}

std::string cancelJobs(const std::vector<std::string>& jobIds) {
    if (jobIds.empty()) return {};
    std::vector<std::string> words{"scancel"};
    words.insert(words.end(), jobIds.begin(), jobIds.end());
    try {
        // Within the time limit, but not stopped by the signal: cancelling is what a stopped vri-run does last.
        const auto [status, output] =
            captureProcess(slurmProgram("scancel"), words, {.in = "/dev/null", .out = {}, .err = {}, .errToOut = true},
                           kLastClientLimits);
        if (status.ok()) return {};
        return "scancel failed (" + status.describe() + "): " + printableShort(firstErrorLine(output));
    } catch (const Error& e) {  // scancel is missing, cannot start or does not answer
        return e.what();
    }
}

}  // namespace vri
