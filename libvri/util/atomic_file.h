#pragma once
// Every output a tool writes goes through here, so that an output never damages what its path names
// and success is claimed only for bytes that reached the file.
//
// What the path names decides how it is written:
//   - nothing, or a regular file: the bytes go to a temporary file beside it, ".STEM.tmp.PID.EXT"
//     (the extension kept: image libraries pick the format from it; an existing file's permission bits
//     kept), which is checked, fsync'ed and renamed over the path; then the directory is fsync'ed.
//     A failed write leaves the old file as it was and removes the temporary file, and so does a SIGINT,
//     SIGTERM or SIGHUP at their default action (a handler, installed with the first temporary file,
//     removes every live one and re-raises the signal); a kill -9 can leave the temporary file behind,
//     never a truncated output, and the next write of the same path removes it once its process is gone
//     (stale_temp_files.h).
//   - a symbolic link: followed to its final target (through chains of links), which is replaced as
//     above, so the link stays a link; a dangling link gets its target created.
//   - a character device, a FIFO, or "-" (stdout): written in place, every write checked; nothing is
//     created beside it and nothing renamed, so /dev/null stays a device. A link that leads to one
//     (/dev/stdout's /proc/self/fd/1 too) is opened through the link. A FIFO blocks until it has a
//     reader, as a shell's redirection does.
//   - anything else (a directory, a socket, a block device): an error naming the path; nothing is written.
// Missing parent directories are created. Every failure is a vri::Error naming `path` and saying why
// (a full disk, a file size limit: SIGXFSZ is ignored from the first write on, so `ulimit -f` makes
// a write fail with EFBIG instead of killing the process without a word).
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vri {

// Writes `text` to `path` as described above. Any bytes, not only text: raw volumes go through it too.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

struct OutputBytes {
    std::filesystem::path path;
    std::string_view bytes;
};
// Writes outputs that belong together (a header and its raw file) so that a failure replaces none
// of them: every file is written and synced beside its target first, then the streams are written,
// and only then is each renamed into place.
void writeTogether(std::span<const OutputBytes> outputs);

// The outputs of one command, kept as they are made and written together at its end (writeTogether):
// a later output that fails (a full disk, a file size limit) leaves every earlier one as it was.
class OutputSet {
public:
    void add(std::filesystem::path path, std::string bytes) { outputs_.push_back({std::move(path), std::move(bytes)}); }
    void write() const;

private:
    std::vector<std::pair<std::filesystem::path, std::string>> outputs_;
};

// For writers that need a file of their own (a library or program that opens, seeks and closes a
// path): calls write(tmp), then puts tmp's bytes at `path` as described above. tmp keeps the target's
// extension and does not exist when write is called; write must create it as a regular file and
// throw if it fails. For a device, FIFO or "-", tmp lies in the system temporary directory and its
// bytes are copied to the stream once write has returned; tmp is removed in every case.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

// Where a write of `path` would put its bytes: a symbolic link's final target (a dangling one's too),
// else the path itself; throws the error that write would (a directory, a socket, a loop of links),
// creating nothing. Tools check every output with it before any work, so that a bad one is refused
// before another is replaced, and two links to one target count as one output.
std::filesystem::path outputTarget(const std::filesystem::path& path);

}  // namespace vri
