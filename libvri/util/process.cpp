// Child processes through posix_spawn, with the redirections as spawn file actions.
#include "libvri/util/process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "libvri/util/error.h"
#include "libvri/util/format.h"

extern char** environ;

namespace vri {

namespace fs = std::filesystem;

namespace {

// Owns a posix_spawn_file_actions_t, so that every path out of startProcess destroys it.
class FileActions {
public:
    FileActions() { posix_spawn_file_actions_init(&actions_); }
    ~FileActions() { posix_spawn_file_actions_destroy(&actions_); }
    FileActions(const FileActions&) = delete;
    FileActions& operator=(const FileActions&) = delete;

    void open(int fd, const fs::path& path, int flags) {
        check(posix_spawn_file_actions_addopen(&actions_, fd, path.c_str(), flags, 0644));
    }
    void dup(int from, int to) { check(posix_spawn_file_actions_adddup2(&actions_, from, to)); }
    const posix_spawn_file_actions_t* get() const { return &actions_; }

private:
    static void check(int error) {
        if (error != 0) throw Error(std::string("cannot prepare a child process: ") + std::strerror(error));
    }
    posix_spawn_file_actions_t actions_;
};

bool isExecutableFile(const fs::path& path) {
    struct stat info {};
    return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// Adds the redirections of `streams`, stdout to `captureFd` when it is not -1.
void redirect(FileActions& actions, const ProcessStreams& streams, int captureFd) {
    constexpr int kWrite = O_WRONLY | O_CREAT | O_TRUNC;
    if (!streams.in.empty()) actions.open(STDIN_FILENO, streams.in, O_RDONLY);
    if (captureFd >= 0)
        actions.dup(captureFd, STDOUT_FILENO);
    else if (!streams.out.empty())
        actions.open(STDOUT_FILENO, streams.out, kWrite);
    if (streams.errToOut)
        actions.dup(STDOUT_FILENO, STDERR_FILENO);
    else if (!streams.err.empty())
        actions.open(STDERR_FILENO, streams.err, kWrite);
}

pid_t spawn(const fs::path& program, const std::vector<std::string>& words, const FileActions& actions) {
    std::vector<char*> argv;
    for (const std::string& w : words)
        argv.push_back(const_cast<char*>(w.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    // glibc reports a failed exec (and a redirection that cannot be opened) here, not as exit 127.
    const int error = posix_spawn(&pid, program.c_str(), actions.get(), nullptr, argv.data(), environ);
    if (error != 0) throw Error(program.string() + ": cannot start: " + std::strerror(error));
    return pid;
}

}  // namespace

ExitStatus ExitStatus::fromWaitStatus(int status, const struct rusage& usage) {
    if (WIFEXITED(status)) return {true, WEXITSTATUS(status), 0, usage.ru_maxrss};
    return {false, 0, WIFSIGNALED(status) ? WTERMSIG(status) : 0, usage.ru_maxrss};
}

std::string ExitStatus::describe() const {
    return exited ? "exit status " + std::to_string(code) : "signal " + std::to_string(signal);
}

std::optional<fs::path> findProgram(const std::string& name) {
    if (name.empty()) return std::nullopt;
    if (name.find('/') != std::string::npos)
        return isExecutableFile(name) ? std::optional<fs::path>(name) : std::nullopt;
    const char* path = std::getenv("PATH");
    const std::string folders = path ? path : "/usr/local/bin:/usr/bin:/bin";  // glibc's execvp default, less "."
    for (std::size_t start = 0;;) {
        const std::size_t end = folders.find(':', start);
        const std::string folder = folders.substr(start, end == std::string::npos ? std::string::npos : end - start);
        const fs::path candidate = (folder.empty() ? fs::path(".") : fs::path(folder)) / name;
        if (isExecutableFile(candidate)) return candidate;
        if (end == std::string::npos) return std::nullopt;
        start = end + 1;
    }
}

bool commandAvailable(const std::string& name) { return findProgram(name).has_value(); }

pid_t startProcess(const fs::path& program, const std::vector<std::string>& words, const ProcessStreams& streams) {
    FileActions actions;
    redirect(actions, streams, -1);
    return spawn(program, words, actions);
}

ExitStatus waitProcess(pid_t pid) {
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0)
        if (errno != EINTR) throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
    return ExitStatus::fromWaitStatus(status, usage);
}

std::pair<pid_t, ExitStatus> waitAnyProcess() {
    int status = 0;
    struct rusage usage {};
    pid_t pid = 0;
    while ((pid = ::wait4(-1, &status, 0, &usage)) < 0)
        if (errno != EINTR) throw Error(std::string("waiting for a child process: ") + std::strerror(errno));
    return {pid, ExitStatus::fromWaitStatus(status, usage)};
}

ExitStatus runProcess(const fs::path& program, const std::vector<std::string>& words, const ProcessStreams& streams) {
    return waitProcess(startProcess(program, words, streams));
}

namespace {

// Stops a child that is past its limits: SIGTERM, then SIGKILL if it has not ended 2 s later; reaped either
// way, so that no signal can reach another process given its pid.
ExitStatus stopProcess(pid_t pid) {
    ::kill(pid, SIGTERM);
    for (int i = 0; i < 100; ++i) {
        int status = 0;
        struct rusage usage {};
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) return ExitStatus::fromWaitStatus(status, usage);
        if (done < 0 && errno != EINTR) throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(pid, SIGKILL);
    return waitProcess(pid);
}

}  // namespace

ExitStatus runProcessWithin(const fs::path& program, const std::vector<std::string>& words, double seconds,
                            bool& timedOut) {
    timedOut = false;
    const pid_t pid = startProcess(program, words);
    if (!(seconds > 0.0)) return waitProcess(pid);
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const auto waited = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    int status = 0;
    struct rusage usage {};
    for (;;) {
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) return ExitStatus::fromWaitStatus(status, usage);
        if (done < 0 && errno != EINTR)
            throw Error("waiting for process " + std::to_string(pid) + ": " + std::strerror(errno));
        if (waited() >= seconds) {
            timedOut = true;
            return stopProcess(pid);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

std::pair<ExitStatus, std::string> captureProcess(const fs::path& program, const std::vector<std::string>& words,
                                                  const ProcessStreams& streams) {
    return captureProcess(program, words, streams, CaptureLimits{});
}

std::pair<ExitStatus, std::string> captureProcess(const fs::path& program, const std::vector<std::string>& words,
                                                  const ProcessStreams& streams, const CaptureLimits& limits) {
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0) throw Error(std::string("cannot create a pipe: ") + std::strerror(errno));
    // Only our end waits without blocking: the child's stays blocking, as every program expects its stdout
    // (a non-blocking one makes a writer that outpaces us fail with EAGAIN).
    ::fcntl(pipeFds[0], F_SETFL, ::fcntl(pipeFds[0], F_GETFL) | O_NONBLOCK);
    pid_t pid = 0;
    try {
        FileActions actions;
        redirect(actions, streams, pipeFds[1]);
        pid = spawn(program, words, actions);
    } catch (...) {
        ::close(pipeFds[0]);
        ::close(pipeFds[1]);
        throw;
    }
    ::close(pipeFds[1]);
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const std::string name = words.empty() ? program.filename().string() : words[0];
    std::string output;
    // Why it must be stopped now, or "" while it may go on.
    const auto overLimit = [&]() -> std::string {
        if (limits.stop && *limits.stop) return name + ": stopped by a signal while it ran";
        if (limits.seconds > 0 && std::chrono::duration<double>(Clock::now() - start).count() > limits.seconds)
            return name + ": no answer within " + exactNumber(limits.seconds) + " s";
        if (limits.maxBytes > 0 && output.size() > limits.maxBytes)
            return name + ": printed more than " + std::to_string(limits.maxBytes) + " bytes";
        return "";
    };
    std::string why;
    char buffer[4096];
    for (bool open = true; open && why.empty(); why = overLimit()) {
        pollfd fd{pipeFds[0], POLLIN, 0};
        ::poll(&fd, 1, 100);  // a signal or 100 ms ends the wait: the limits are checked at least that often
        ssize_t n = 0;
        while ((n = ::read(pipeFds[0], buffer, sizeof buffer)) > 0) {
            output.append(buffer, static_cast<std::size_t>(n));
            if (limits.maxBytes > 0 && output.size() > limits.maxBytes) break;  // a writer faster than us
        }
        open = n != 0;  // 0: end of output; -1: nothing more now (EAGAIN) or a signal (EINTR)
    }
    ::close(pipeFds[0]);
    // Its output closed, it may still run (a client that closes stdout and hangs): waited for within the limits.
    while (why.empty()) {
        int status = 0;
        struct rusage usage {};
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) return {ExitStatus::fromWaitStatus(status, usage), std::move(output)};
        if (done < 0 && errno != EINTR) throw Error("waiting for " + name + ": " + std::strerror(errno));
        why = overLimit();
        if (why.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    stopProcess(pid);
    throw Error(why);
}

std::filesystem::path thisProgramFolder() {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) throw Error("/proc/self/exe: cannot read where this program is: " + error.message());
    return self.parent_path();
}

}  // namespace vri
