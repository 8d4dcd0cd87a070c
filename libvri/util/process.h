#pragma once
// Starting other programs (gnuplot, git, curl, the tools of an experiment's steps) with an argument
// vector and posix_spawn: no shell ever reads a word, so no character of a name or path can run as
// code. Standard streams are inherited unless redirected to a file.
#include <sys/resource.h>
#include <sys/types.h>

#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vri {

// How a child's standard streams are set up; an empty path inherits the stream from this process.
struct ProcessStreams {
    std::filesystem::path in;   // read from this file
    std::filesystem::path out;  // created or truncated (mode 0644)
    std::filesystem::path err;  // likewise; ignored when errToOut
    bool errToOut = false;      // stderr joins stdout (the same file, or the same captured text)
};

// How a child ended, from wait4's status and resource usage.
struct ExitStatus {
    bool exited = false;  // by exit(): `code` holds its status; else killed by `signal`
    int code = 0;
    int signal = 0;
    // The largest resident set of the child, or of a process it waited for (wait4's ru_maxrss), in KiB. At
    // least this process's own peak at the spawn: Linux records the memory a child shares with its parent
    // (posix_spawn's child does until its exec) as the child's.
    long long peakRssKiB = 0;

    static ExitStatus fromWaitStatus(int status, const struct rusage& usage);
    bool ok() const { return exited && code == 0; }
    std::string describe() const;  // "exit status 3", "signal 9"
};

// The file `name` names as a program: a name with a '/' is taken as it is, any other is looked up
// in the folders of $PATH as execvp would (an empty entry is the current folder). nullopt when no
// executable regular file is found.
std::optional<std::filesystem::path> findProgram(const std::string& name);

// The folder of this process's own executable (/proc/self/exe): where vri's tools find each other.
// Throws vri::Error when it cannot be read.
std::filesystem::path thisProgramFolder();

// Whether findProgram finds `name` (gnuplot, curl, ...).
bool commandAvailable(const std::string& name);

// Starts `program` (a path, not looked up in PATH) with argv = words (words[0] is what the child sees
// as its name). Throws vri::Error naming the program when it cannot be started.
pid_t startProcess(const std::filesystem::path& program, const std::vector<std::string>& words,
                   const ProcessStreams& streams = {});

// Waits for the child `pid` (retrying on EINTR).
ExitStatus waitProcess(pid_t pid);
// Waits for any child of this process: which one, and how it ended.
std::pair<pid_t, ExitStatus> waitAnyProcess();

// Starts `program` and waits for it.
ExitStatus runProcess(const std::filesystem::path& program, const std::vector<std::string>& words,
                      const ProcessStreams& streams = {});

// Starts `program` and waits for it at most `seconds`: past that it is sent SIGTERM, and SIGKILL 2 s later
// if it still runs; `timedOut` says whether it was stopped so. seconds <= 0 waits without a limit.
ExitStatus runProcessWithin(const std::filesystem::path& program, const std::vector<std::string>& words, double seconds,
                            bool& timedOut);

// Runs `program` with its stdout captured (streams.out is ignored; streams.errToOut captures stderr
// too): its exit status and everything it printed.
std::pair<ExitStatus, std::string> captureProcess(const std::filesystem::path& program,
                                                  const std::vector<std::string>& words,
                                                  const ProcessStreams& streams = {});

// How long a captured program may run, how much it may print, and a flag that ends the wait at once (a
// signal handler's: SIGTERM must stop a vri-run that waits on a client that never answers).
struct CaptureLimits {
    double seconds = 0;                                  // > 0: the most it may run
    std::size_t maxBytes = 0;                            // > 0: the most it may print
    const volatile std::sig_atomic_t* stop = nullptr;    // non-zero: stop now
};

// captureProcess within `limits`: a program that runs too long, prints too much or is asked to stop is
// sent SIGTERM, SIGKILL 2 s later, waited for, and the call throws vri::Error "<name>: no answer within N s",
// "<name>: printed more than N bytes" or "<name>: stopped by a signal while it ran" (name: words[0]).
std::pair<ExitStatus, std::string> captureProcess(const std::filesystem::path& program,
                                                  const std::vector<std::string>& words, const ProcessStreams& streams,
                                                  const CaptureLimits& limits);

}  // namespace vri
