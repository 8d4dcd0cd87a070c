#pragma once
// What runs inside the Slurm jobs vri-run submits (vri-run's hidden --slurm-node-steps and
// --slurm-node-check): the job's steps one after another, each leaving a status file that vri-run
// reads back over the shared file system; and the check, once per run, that a compute node sees the
// tools, the inputs and the results folder as the submitting host does.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vri {

// One step of a job: the exact command of the local executor, run from `workDir`.
struct NodeStep {
    std::string id;
    std::filesystem::path program;
    std::vector<std::string> words;
    std::filesystem::path log;     // stdout and stderr of the step
    std::filesystem::path status;  // written when the step ends (NodeStepStatus), kept beside its record
};

struct NodeSteps {
    std::filesystem::path workDir;
    std::vector<NodeStep> steps;
    std::filesystem::path digestRecord;  // VRI_INPUT_DIGESTS for the steps (input_digest.h)
};

void writeNodeSteps(const std::filesystem::path& file, const NodeSteps& steps);
NodeSteps readNodeSteps(const std::filesystem::path& file);

// How a step ended on its node. The file also holds "started_epoch" and "ended_epoch" (seconds since
// the epoch on the node's clock), for a reader who checks the order steps ran in.
struct NodeStepStatus {
    bool exited = false;  // by exit(): `code`; else killed by `signal`
    int code = 0;
    int signal = 0;
    double wallSeconds = 0;
    std::string node;   // the host it ran on
    std::string jobId;  // $SLURM_JOB_ID
    long long peakRssKiB = 0;  // the step's largest resident memory (ExitStatus::peakRssKiB)
};
// nullopt while there is no such file (or not yet a whole one).
std::optional<NodeStepStatus> readNodeStepStatus(const std::filesystem::path& file);

// Runs the steps in order, each with its log and then its status file; stops at the first that
// fails. Returns the job's exit code: 0 when every step succeeded, else 1.
int runNodeSteps(const std::filesystem::path& file);

// What the first job checks: each tool's SHA-512 as vri-run's host sees it, each input file's size,
// and that it can write `report` (in the results root) with `token` in it.
struct NodeCheck {
    std::string token;
    std::vector<std::pair<std::filesystem::path, std::string>> tools;  // path, SHA-512
    std::vector<std::pair<std::filesystem::path, std::uintmax_t>> files;  // path, size in bytes
    std::filesystem::path report;
};
void writeNodeCheck(const std::filesystem::path& file, const NodeCheck& check);

// Runs the check of `file` and writes its report: {"token", "node", "problems": [one line each]}.
// Returns 0 once the report is written, whatever it says, so that the job's state tells vri-run
// whether to wait for a report (a shared file system may show it late) or that none will come.
int runNodeCheck(const std::filesystem::path& file);

// The report's problems, or a vri::Error when there is no report carrying `token`: the node could not
// write into the results root or does not share it.
std::vector<std::string> readNodeCheckReport(const NodeCheck& check);

}  // namespace vri
