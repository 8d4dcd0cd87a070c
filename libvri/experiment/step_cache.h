#pragma once
// When a step may be skipped. A step's key is the SHA-512 of its tool's name and binary, its
// arguments, the engine_environment.h variables that are set, and for each input either the file's SHA-512 (a source:
// volume, transfer function, plot spec) or the key of the step that writes it (so a change upstream changes every key below it
// without running anything). A step is skipped when the record of its last successful run, kept
// in <results>/.steps/<id>.json, has the same key, the same input digests as the files now, and
// every output still present with the digest recorded. A record is written only after its step
// succeeded and removed before it runs again, so an interrupted run leaves nothing to trust.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/util/input_digest.h"

namespace vri {

// SHA-512 of files, each read once per process unless forgotten (a step rewrote it).
class FileHasher {
public:
    // The digest, or "missing" when there is no such file.
    const std::string& digest(const std::filesystem::path& path);
    // The size and time the file had before digest() hashed it; nullopt when it was missing or not hashed.
    std::optional<FileStamp> stamp(const std::filesystem::path& path) const;
    void forget(const std::filesystem::path& path) { files_.erase(path); }

private:
    struct Hashed {
        std::string digest;
        std::optional<FileStamp> stamp;  // nullopt for a missing file
    };
    std::map<std::filesystem::path, Hashed> files_;
};

// The keys of all steps of a plan, in plan order; tools are looked up in `toolDir`.
std::vector<std::string> stepKeys(const Plan& plan, const std::filesystem::path& toolDir, FileHasher& hasher);

struct FileDigest {
    std::string path;  // as the command names it
    std::string sha512;
};

// [{"path", "sha512"}, ...], as records and manifests list files.
nlohmann::json toJson(const std::vector<FileDigest>& files);

// Where a step ran: vri-run's own child process ("local") or a Slurm job ("slurm", with the job's id
// and the state Slurm ended it in), on which host.
struct StepExecution {
    std::string executor = "local";
    std::string node;
    std::string jobId;     // Slurm only
    std::string jobState;  // Slurm only: COMPLETED, FAILED, TIMEOUT, CANCELLED, ...
    // The node's 1-minute load average when the step started and when it ended (local executor): a time
    // measured beside other work says so.
    std::optional<double> loadBefore, loadAfter;
    // The steps of its plan that ran while it ran (local executor, --jobs above 1): never beside a step
    // that runs alone (Step::alone).
    std::vector<std::string> beside;
    // Slurm, --slurm-retries: the attempts before the one that ran it ("job 12 NODE_FAIL on n3").
    std::vector<std::string> earlierAttempts;
    // The step's largest resident memory (its process's, wait4's ru_maxrss), in MiB; where known.
    std::optional<double> peakRssMiB;
};
nlohmann::json toJson(const StepExecution& execution);
// A peak resident memory in KiB (ExitStatus::peakRssKiB) as a record holds it: MiB to 0.1; nullopt for 0, not known.
std::optional<double> peakRssMiB(long long kib);

// What a successful run of a step left behind.
struct StepRecord {
    std::string key;
    std::string command;  // the shell line
    std::vector<FileDigest> inputs, outputs;
    double wallSeconds = 0;
    std::string ranUtc;
    StepExecution execution;
};

std::filesystem::path recordPath(const Plan& plan, const Step& step);  // <results>/.steps/<id>.json
std::optional<StepRecord> readRecord(const std::filesystem::path& path);  // nullopt when absent or unreadable
void writeRecord(const std::filesystem::path& path, const StepRecord& record);  // atomically

// Digests of files in the order given, named as the step's command names them.
std::vector<FileDigest> digestFiles(const Plan& plan, const std::vector<std::filesystem::path>& files, FileHasher& hasher);

// True when `record` shows a run of the step with this key whose inputs and outputs are as now.
bool recordIsCurrent(const StepRecord& record, const std::string& key, const Plan& plan, const Step& step,
                     FileHasher& hasher);

}  // namespace vri
