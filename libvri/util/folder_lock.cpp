// An exclusive flock on a file in the folder, with the holder's pid in it for the second comer's message.
#include "libvri/util/folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// "pid 1234: vri-run --quick exp.yaml" from the lock file and /proc, as much as can be found (guardedMain
// escapes any control character of the command).
std::string holder(int fd) {
    char text[32] = {};
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    const std::string pid =
        n > 0 ? std::string(text, static_cast<std::size_t>(n)).substr(0, std::string(text).find('\n')) : "";
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return "pid unknown";
    std::ostringstream raw;
    raw << std::ifstream("/proc/" + pid + "/cmdline", std::ios::binary).rdbuf();
    std::string command = raw.str();
    while (!command.empty() && command.back() == '\0')
        command.pop_back();
    if (command.size() > 300) command = command.substr(0, 300) + "...";
    std::replace(command.begin(), command.end(), '\0', ' ');  // between the words
    return "pid " + pid + (command.empty() ? "" : ": " + command);
}

}  // namespace

FolderLock::FolderLock(const fs::path& folder) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(folder.string() + ": cannot create the folder: " + ec.message());
    const fs::path file = folder / kFolderLockName;
    // O_CLOEXEC: the steps must not inherit the lock, or one left running would hold it after vri-run died.
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (fd_ < 0) throw Error(file.string() + ": cannot open the lock file: " + std::strerror(errno));
    struct stat info {};
    if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd_);
        throw Error(file.string() + ": the lock file must be a regular file");
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        const std::string message = error == EWOULDBLOCK ? folder.string() + ": in use by another vri-run (" +
                                                               holder(fd_) + "); wait for it to finish, or stop it"
                                                         : file.string() + ": cannot lock: " + std::strerror(error);
        ::close(fd_);
        throw Error(message);
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
        const int error = errno;
        ::close(fd_);
        throw Error(file.string() + ": cannot write the lock file: " + std::strerror(error));
    }
}

FolderLock::~FolderLock() { ::close(fd_); }

}  // namespace vri
