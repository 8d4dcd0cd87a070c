// Finding writeAtomically's temporary files by name and asking the kernel whether their writer lives.
#include "libvri/util/stale_temp_files.h"

#include <signal.h>
#include <sys/types.h>

#include <cerrno>
#include <charconv>
#include <optional>
#include <string_view>

namespace vri {

namespace fs = std::filesystem;

namespace {

// The PID of ".NAME.tmp.PID" or ".NAME.tmp.PID.EXT", else nullopt.
std::optional<pid_t> writerPid(std::string_view name) {
    if (name.size() < 2 || name.front() != '.') return std::nullopt;
    for (std::size_t at = name.find(".tmp.", 1); at != std::string_view::npos; at = name.find(".tmp.", at + 1)) {
        const std::string_view rest = name.substr(at + 5);
        pid_t pid = 0;
        const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), pid);
        if (at > 1 && error == std::errc() && end != rest.data() && pid > 0 &&
            (end == rest.data() + rest.size() || *end == '.'))
            return pid;
    }
    return std::nullopt;
}

bool processGone(pid_t pid) { return ::kill(pid, 0) != 0 && errno == ESRCH; }

}  // namespace

std::vector<fs::path> removeStaleTempFiles(const fs::path& folder) {
    std::vector<fs::path> removed;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
        const auto pid = writerPid(entry.path().filename().string());
        if (!pid || !entry.is_regular_file(ec) || entry.is_symlink(ec) || !processGone(*pid)) continue;
        if (fs::remove(entry.path(), ec)) removed.push_back(entry.path());
    }
    return removed;
}

}  // namespace vri
