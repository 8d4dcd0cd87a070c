#pragma once
// One vri-run at a time per experiment folder. Two runs writing one folder would each record digests
// of files the other then replaces, and leave a manifest that does not match the files on disk; so
// vri-run holds an exclusive flock on <folder>/.vri-run.lock while it works there, and a second run
// stops at once, saying which process holds it (waiting would look like a hang in CI, and the
// second run would then only find the first one's results cached). The kernel drops a lock when
// its holder dies, even by kill -9: a stale lock file is never in the way.
#include <filesystem>

namespace vri {

class FolderLock {
public:
    // Creates `folder` if need be and locks it; throws vri::Error "FOLDER: in use by another vri-run
    // (pid N: COMMAND) ..." when another process holds the lock.
    explicit FolderLock(const std::filesystem::path& folder);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int fd_ = -1;
};

// The lock file's name in a locked folder.
inline constexpr const char* kFolderLockName = ".vri-run.lock";

}  // namespace vri
