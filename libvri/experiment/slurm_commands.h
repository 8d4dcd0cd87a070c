#pragma once
// Slurm's own commands, as vri-run uses them: sbatch to submit, squeue to watch, scancel to cancel.
// Every word goes to them as an argument vector (util/process.h), never through a shell. Slurm's
// commands find their cluster as usual (SLURM_CONF, /etc/slurm/slurm.conf).
#include <csignal>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vri {

// A job as squeue shows it.
struct SlurmJob {
    std::string id;
    std::string state;   // PENDING, RUNNING, COMPLETED, FAILED, TIMEOUT, CANCELLED, ...
    std::string node;    // the node list, empty while pending
    std::string reason;  // why it waits or ended: None, Dependency, DependencyNeverSatisfied, NonZeroExitCode, ...
    int restarts = 0;    // how often Slurm requeued it (after its node failed, or preempted): squeue's RestartCnt
};

// True for a state a job does not leave: COMPLETED, FAILED, TIMEOUT, CANCELLED, PREEMPTED (not
// requeued), NODE_FAIL, OUT_OF_MEMORY, BOOT_FAIL, DEADLINE, REVOKED, SPECIAL_EXIT; false for one it leaves
// (PENDING, RUNNING, COMPLETING, whose epilog still runs, SUSPENDED, REQUEUED, ...). Any other is a
// vri::Error naming it: counted as running, it would be waited on for ever.
bool isFinalJobState(const std::string& state);

// What slurmstepd wrote into a job's output (`text`) when it killed the job for exceeding its memory: the
// first "exceeded memory limit (USED > LIMIT)" line from "StepId=" on, or nullopt. Where memory is enforced
// by jobacct_gather (JobAcctGatherParams=OverMemoryKill, no cgroups) Slurm then ends the job FAILED
// (JobLaunchFailure), not OUT_OF_MEMORY, and this line is the only sign of the cause.
std::optional<std::string> memoryLimitKill(const std::string& text);

// squeue's arguments for these jobs, in every state it still knows them (--states=all), one line each.
std::vector<std::string> squeueArguments(const std::vector<std::string>& jobIds);
// The jobs in squeue's output for squeueArguments(), by id. A line that is not one is a vri::Error.
std::map<std::string, SlurmJob> parseSqueue(const std::string& output);

// The job id sbatch --parsable printed ("12" or "12;cluster"), below 2^32 as Slurm's are. Anything else is
// a vri::Error.
std::string parseSbatchJobId(const std::string& output);

// Checks a site's or user's sbatch option (--slurm-arg, VRI_SLURM_ARGS) against an allow-list, as sbatch's
// parser would read the word: one long option whose name is whole (no abbreviation, which getopt_long would
// stretch to another option), with its value after '=' when it takes one (a value-less --comment would take
// the job script as its value). Allowed: what the jobs ask for (--account, --qos, --partition, --time,
// --mem, --gres, --constraint, --exclusive, ...: the list in slurm_commands.cpp and docs/cluster.md). A
// short option is refused (sbatch reads -vo<path> as -v -o <path>), and so is one of the options vri-run
// sets itself (--dependency, --output, --chdir, --array, --job-name, ...), named as such. The refusal is a
// vri::Error naming `source`.
void checkSiteSbatchOption(const std::string& option, const std::string& source);

// The signal that asked vri-run to stop while it runs Slurm jobs (set by the executor's handler,
// slurm_executor.cpp), 0 for none: a client call in progress (sbatch, squeue) then ends at once.
extern volatile std::sig_atomic_t gSlurmInterrupt;

// The most a Slurm client call may take, and print: a client that never answers, or answers without end,
// must not hang vri-run (Slurm's own MessageTimeout is 10 s; a busy controller can take a few of them).
inline constexpr double kSlurmClientSeconds = 120;
inline constexpr std::size_t kSlurmClientBytes = std::size_t(16) << 20;

// Runs sbatch with `arguments` (options, then the script and its arguments) and returns the job id.
// A refusal is a vri::Error with sbatch's own first line.
std::string submitJob(const std::vector<std::string>& arguments);
// The jobs' states; a job squeue no longer knows is absent from the map. squeue failing otherwise (the
// controller not answering) is a vri::Error.
// `interruptible`: squeue is stopped when a signal sets gSlurmInterrupt; false for the queries made after
// one, while a stopped vri-run waits for the jobs it cancelled to end.
std::map<std::string, SlurmJob> queryJobs(const std::vector<std::string>& jobIds, bool interruptible = true);
// This user's jobs that squeue shows not ended and whose working directory is `workDir`: those of an
// earlier vri-run on the same results folder that it could not cancel (it was killed with SIGKILL).
std::vector<std::string> unendedJobsIn(const std::filesystem::path& workDir);
// The lines of `squeue --Format=JobID:|,State:|,WorkDir:` (the directory last, whatever it holds): the ids of
// jobs not ended in `workDir`.
std::vector<std::string> parseUnendedIn(const std::string& output, const std::string& workDir);
// scancel for these jobs: "" when scancel succeeded, else what went wrong ("scancel failed (exit status 1):
// its first error line"); a job that ended meanwhile also fails it, so only squeue tells whether the jobs ended.
std::string cancelJobs(const std::vector<std::string>& jobIds);

}  // namespace vri
