#include "libvri/util/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libvri/util/error.h"
#include "libvri/util/stale_temp_files.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// Linux's own limit on the links one path lookup follows (MAXSYMLINKS).
constexpr int kMaxSymlinkHops = 40;

enum class TargetKind { File, Stream, Stdout };

// Where the bytes for a user's output path end up.
struct Target {
    fs::path path;  // the path written: the final target of a symlink
    TargetKind kind = TargetKind::File;
    std::optional<mode_t> keptMode;  // permission bits of the regular file being replaced
};

[[noreturn]] void fail(const fs::path& path, const std::string& what, int error) {
    throw Error(path.string() + ": " + what + ": " + std::strerror(error));
}

// With the default action a write past RLIMIT_FSIZE kills the process before write() can report EFBIG.
void ignoreFileSizeSignal() {
    static const bool ignored = [] {
        std::signal(SIGXFSZ, SIG_IGN);
        return true;
    }();
    (void)ignored;
}

std::string kindName(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISBLK(mode)) return "a block device";
    return "not a regular file";
}

void createParentDirectories(const fs::path& userPath, const fs::path& file) {
    const fs::path dir = file.parent_path();
    std::error_code ec;
    if (dir.empty() || fs::is_directory(dir, ec)) return;
    fs::create_directories(dir, ec);
    if (ec) throw Error(userPath.string() + ": cannot create directory " + dir.string() + ": " + ec.message());
}

// With createParents false nothing is created: outputTarget's check before any work.
Target resolveTarget(const fs::path& userPath, bool createParents = true) {
    if (userPath == "-") return {userPath, TargetKind::Stdout, std::nullopt};
    // A device or FIFO is opened through its links: /dev/stdout's /proc/self/fd/1 names no path to walk.
    struct stat followed {};
    if (::stat(userPath.c_str(), &followed) == 0 && (S_ISCHR(followed.st_mode) || S_ISFIFO(followed.st_mode)))
        return {userPath, TargetKind::Stream, std::nullopt};
    fs::path path = userPath;
    for (int hops = 0;; ++hops) {
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0) {
            if (errno != ENOENT) fail(userPath, "cannot write", errno);
            if (createParents) createParentDirectories(userPath, path);
            return {path, TargetKind::File, std::nullopt};
        }
        if (S_ISREG(st.st_mode)) return {path, TargetKind::File, st.st_mode & 07777};
        if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {path, TargetKind::Stream, std::nullopt};
        if (!S_ISLNK(st.st_mode))
            throw Error(userPath.string() + ": cannot write: it is " + kindName(st.st_mode) +
                        "; expected a regular file, a character device, a FIFO or '-'");
        if (hops == kMaxSymlinkHops) fail(userPath, "cannot write", ELOOP);
        std::error_code ec;
        const fs::path link = fs::read_symlink(path, ec);
        if (ec) throw Error(userPath.string() + ": cannot read symbolic link: " + ec.message());
        path = link.is_absolute() ? link : path.parent_path() / link;
    }
}

// Writes all of `bytes`, resuming after short writes and signals.
void writeAll(int fd, std::string_view bytes, const fs::path& userPath) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(userPath, "cannot write", errno);
        }
        bytes.remove_prefix(static_cast<std::size_t>(n));
    }
}

// fsync, where the file system can: EINVAL means it keeps no such state for this file.
void syncDescriptor(int fd, const fs::path& userPath, const std::string& what) {
    if (::fsync(fd) != 0 && errno != EINVAL) fail(userPath, what, errno);
}

void closeChecked(int fd, const fs::path& userPath) {
    // Linux releases the descriptor even when close() fails, so it is never retried.
    if (::close(fd) != 0 && errno != EINTR) fail(userPath, "cannot write", errno);
}

// An open descriptor that is closed, unchecked, when an error unwinds past it.
class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }
    void close(const fs::path& userPath) { closeChecked(std::exchange(fd_, -1), userPath); }

private:
    int fd_;
};

// The temporary file beside `target`: hidden, named after the process, with the target's extension.
// A stale one of the same target, left by a writer that is gone, is removed first: the next run of the
// tool cleans up after a kill -9.
fs::path temporaryBeside(const fs::path& target) {
    removeStaleTempFiles(target);
    return temporaryFileFor(target, ::getpid());
}

// The temporary files that exist right now, for a handler of SIGINT, SIGTERM and SIGHUP to remove before
// the process dies. A handler may only call async-signal-safe functions (no allocation, no locks), so the
// paths live in fixed slots that it reads as they are; each slot's state says whether its path is whole.
constexpr std::size_t kLiveSlots = 64;  // writeTogether's outputs at once, and writers on other threads
enum SlotState : int { kFree, kFilling, kLive };
struct LiveSlot {
    std::atomic<int> state{kFree};
    char file[PATH_MAX];
    char privateDir[PATH_MAX];  // empty, or the directory that holds file, removed after it
};
LiveSlot gLiveSlots[kLiveSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the handler reads the slot states");

extern "C" void removeLiveTemporaryFiles(int signal) {
    for (LiveSlot& slot : gLiveSlots)
        if (slot.state.load(std::memory_order_acquire) == kLive) {
            ::unlink(slot.file);
            if (slot.privateDir[0] != '\0') ::rmdir(slot.privateDir);
        }
    // SA_RESETHAND restored the default action: the signal, blocked until this returns, then ends the
    // process as it would have without the handler (the parent sees the signal, not an exit code).
    ::raise(signal);
}

// Installs the handler for the signals that end a process by default, once; a signal the program
// ignores (nohup) or handles itself (vri-run's Slurm executor, which unwinds, so destructors clean up)
// keeps its disposition.
void removeTemporaryFilesOnSignals() {
    static const bool installed = [] {
        for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction current {};
            if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) continue;
            struct sigaction action {};
            action.sa_handler = removeLiveTemporaryFiles;
            sigemptyset(&action.sa_mask);
            action.sa_flags = SA_RESETHAND;
            ::sigaction(signal, &action, nullptr);
        }
        return true;
    }();
    (void)installed;
}

// Copies `path` (absolute, so that it means the same in the handler whatever happens to the working
// directory) into a slot's buffer; false when it does not fit.
bool copyPath(const fs::path& path, char (&buffer)[PATH_MAX]) {
    std::error_code ec;
    const std::string absolute = path.empty() ? std::string() : fs::absolute(path, ec).string();
    if (ec || absolute.size() >= PATH_MAX) return false;
    std::memcpy(buffer, absolute.c_str(), absolute.size() + 1);
    return true;
}

// Removes a temporary file, and the private directory it lies in if any, unless released; a signal that
// ends the process meanwhile removes them too (unless every slot is taken or the path is too long: then
// only a kill can leave the file, and the next write of the same target removes it).
class TemporaryFile {
public:
    TemporaryFile(fs::path file, fs::path privateDir = {})
        : file_(std::move(file)), privateDir_(std::move(privateDir)) {
        removeTemporaryFilesOnSignals();
        for (LiveSlot& slot : gLiveSlots) {
            int expected = kFree;
            if (!slot.state.compare_exchange_strong(expected, kFilling, std::memory_order_acquire)) continue;
            if (copyPath(file_, slot.file) && copyPath(privateDir_, slot.privateDir)) {
                slot.state.store(kLive, std::memory_order_release);
                slot_ = &slot;
            } else {
                slot.state.store(kFree, std::memory_order_release);
            }
            break;
        }
    }
    ~TemporaryFile() {
        std::error_code ignored;
        if (!file_.empty()) fs::remove(file_, ignored);
        if (!privateDir_.empty()) fs::remove_all(privateDir_, ignored);
        release();
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const fs::path& path() const { return file_; }
    // The file is no longer ours to remove: renamed into place, or never created.
    void disown() {
        file_.clear();
        release();
    }

private:
    // After the file is gone or renamed: a signal in between unlinks a name that no longer exists.
    void release() {
        if (slot_) std::exchange(slot_, nullptr)->state.store(kFree, std::memory_order_release);
    }

    fs::path file_;
    fs::path privateDir_;
    LiveSlot* slot_ = nullptr;
};

// Renames the synced temporary file over the target, then syncs the directory so that the rename
// itself survives a crash.
void moveIntoPlace(TemporaryFile& tmp, const Target& target, const fs::path& userPath) {
    if (::rename(tmp.path().c_str(), target.path.c_str()) != 0)
        fail(userPath, "cannot rename temporary file into place", errno);
    tmp.disown();
    const fs::path dir = target.path.parent_path().empty() ? fs::path(".") : target.path.parent_path();
    Descriptor dirFd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dirFd.get() < 0) fail(userPath, "cannot sync directory " + dir.string(), errno);
    syncDescriptor(dirFd.get(), userPath, "cannot sync directory " + dir.string());
}

// Opens a device or FIFO for writing (checking that it is still one once open), lets fill write to
// it, and closes it checked. Stdout is flushed first, so that what the tool printed before stays before.
void writeStream(const Target& target, const fs::path& userPath, const std::function<void(int fd)>& fill) {
    if (target.kind == TargetKind::Stdout) {
        std::cout.flush();
        if (std::fflush(stdout) != 0 || !std::cout) fail(userPath, "cannot write to stdout", errno);
        return fill(STDOUT_FILENO);
    }
    Descriptor stream(::open(target.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
    if (stream.get() < 0) fail(userPath, "cannot open for writing", errno);
    struct stat st {};
    if (::fstat(stream.get(), &st) != 0 || !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)))
        throw Error(userPath.string() + ": cannot write: it stopped being a character device or FIFO");
    fill(stream.get());
    stream.close(userPath);
}

// Copies a file this process wrote to a stream, a chunk at a time.
void copyToStream(const fs::path& file, const Target& target, const fs::path& userPath) {
    Descriptor in(::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW));
    if (in.get() < 0) fail(userPath, "cannot read back what was written", errno);
    writeStream(target, userPath, [&](int out) {
        std::vector<char> chunk(1 << 20);
        for (;;) {
            const ssize_t n = ::read(in.get(), chunk.data(), chunk.size());
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) fail(userPath, "cannot read back what was written", errno);
            if (n == 0) return;
            writeAll(out, std::string_view(chunk.data(), static_cast<std::size_t>(n)), userPath);
        }
    });
}

// The writer must have left a regular file at tmp: a program that fails without saying so leaves none.
void requireWritten(const fs::path& tmp, const fs::path& userPath) {
    struct stat st {};
    if (::lstat(tmp.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        throw Error(userPath.string() + ": cannot write: the writer produced no file");
}

// Writes the bytes to a temporary file beside the target, synced and closed: all but the rename.
std::unique_ptr<TemporaryFile> stageBeside(const Target& target, const OutputBytes& output) {
    const fs::path tmpPath = temporaryBeside(target.path);
    // A leftover of a dead process that had our PID is ours to replace; O_EXCL then refuses anything
    // put there meanwhile, and O_NOFOLLOW a link planted at the name.
    ::unlink(tmpPath.c_str());
    // A new file gets 0666 less the umask, as open() gives; a replaced one keeps its bits.
    // Registered before it exists, so that no signal finds it unregistered.
    auto tmp = std::make_unique<TemporaryFile>(tmpPath);
    Descriptor out(::open(tmpPath.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666));
    if (out.get() < 0) {
        const int error = errno;
        tmp->disown();  // what is at the name is not ours
        fail(output.path, "cannot create temporary file " + tmpPath.string(), error);
    }
    if (target.keptMode && ::fchmod(out.get(), *target.keptMode) != 0)
        fail(output.path, "cannot keep the file's mode", errno);
    writeAll(out.get(), output.bytes, output.path);
    syncDescriptor(out.get(), output.path, "cannot sync");
    out.close(output.path);
    return tmp;
}

}  // namespace

void writeTogether(std::span<const OutputBytes> outputs) {
    ignoreFileSizeSignal();
    std::vector<Target> targets;
    std::vector<fs::path> files;  // per output, the file it is staged beside; empty for a stream
    for (const OutputBytes& output : outputs) {
        const Target& target = targets.emplace_back(resolveTarget(output.path));
        files.push_back(target.kind == TargetKind::File ? fs::absolute(target.path).lexically_normal() : fs::path());
        // Two outputs staged at one target would share its temporary file: the tools refuse this with the
        // options' names (cli.h's requireDistinctOutputs); this is the last guard.
        for (std::size_t j = 0; j + 1 < files.size(); ++j)
            if (!files.back().empty() && files[j] == files.back())
                throw Error(output.path.string() + ": cannot write: it is also " + outputs[j].path.string() +
                            ", written by the same command");
    }
    std::vector<std::unique_ptr<TemporaryFile>> staged(outputs.size());
    for (std::size_t i = 0; i < outputs.size(); ++i)
        if (targets[i].kind == TargetKind::File) staged[i] = stageBeside(targets[i], outputs[i]);
    for (std::size_t i = 0; i < outputs.size(); ++i)
        if (targets[i].kind != TargetKind::File)
            writeStream(targets[i], outputs[i].path, [&](int fd) { writeAll(fd, outputs[i].bytes, outputs[i].path); });
    for (std::size_t i = 0; i < outputs.size(); ++i)
        if (staged[i]) moveIntoPlace(*staged[i], targets[i], outputs[i].path);
}

void OutputSet::write() const {
    std::vector<OutputBytes> views;
    for (const auto& [path, bytes] : outputs_) views.push_back({path, bytes});
    writeTogether(views);
}

void writeTextFile(const fs::path& path, std::string_view text) {
    const OutputBytes output{path, text};
    writeTogether({&output, 1});
}

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    ignoreFileSizeSignal();
    const Target target = resolveTarget(path);
    if (target.kind != TargetKind::File) {
        // A private directory: nobody else can put anything at the temporary name.
        std::error_code ec;
        const fs::path systemTmp = fs::temp_directory_path(ec);
        if (ec) throw Error(path.string() + ": no temporary directory to write through: " + ec.message());
        std::string pattern = (systemTmp / "vri-output.XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) fail(path, "cannot create a temporary directory", errno);
        const fs::path dir = pattern;
        const std::string name = path == "-" ? "stdout" : path.filename().string();
        TemporaryFile tmp(dir / name, dir);
        write(tmp.path());
        requireWritten(tmp.path(), path);
        return copyToStream(tmp.path(), target, path);
    }
    TemporaryFile tmp(temporaryBeside(target.path));
    ::unlink(tmp.path().c_str());  // a leftover of a dead process that had our PID
    write(tmp.path());
    requireWritten(tmp.path(), path);
    Descriptor written(::open(tmp.path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW));
    if (written.get() < 0) fail(path, "cannot open what was written", errno);
    if (target.keptMode && ::fchmod(written.get(), *target.keptMode) != 0)
        fail(path, "cannot keep the file's mode", errno);
    syncDescriptor(written.get(), path, "cannot sync");
    written.close(path);
    moveIntoPlace(tmp, target, path);
}

fs::path outputTarget(const fs::path& path) { return resolveTarget(path, false).path; }

}  // namespace vri
