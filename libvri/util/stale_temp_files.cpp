// Naming writeAtomically's temporary files, finding them by name and asking the kernel whether their
// writer lives.
#include "libvri/util/stale_temp_files.h"

#include <signal.h>

#include <cerrno>
#include <charconv>
#include <string>
#include <string_view>

namespace vri {

namespace fs = std::filesystem;

namespace {

// ".STEM.tmp." and EXT: what every temporary file of `target` starts and ends with.
struct TemporaryName {
    std::string prefix, suffix;
};

TemporaryName temporaryName(const fs::path& target) {
    // Appended piece by piece: `"." + std::string` trips a false -Wrestrict in GCC 12.
    std::string prefix = ".";
    prefix += target.stem().string();
    prefix += ".tmp.";
    return {prefix, target.extension().string()};
}

bool processGone(pid_t pid) { return ::kill(pid, 0) != 0 && errno == ESRCH; }

}  // namespace

fs::path temporaryFileFor(const fs::path& target, pid_t pid) {
    const TemporaryName name = temporaryName(target);
    return fs::path(target).replace_filename(name.prefix + std::to_string(pid) + name.suffix);
}

std::vector<fs::path> removeStaleTempFiles(const fs::path& target) {
    const TemporaryName name = temporaryName(target);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::vector<fs::path> removed;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
        const std::string file = entry.path().filename().string();
        if (file.size() <= name.prefix.size() + name.suffix.size() || !file.starts_with(name.prefix) ||
            !file.ends_with(name.suffix))
            continue;
        // Exactly the decimal pid writeAtomically prints between them: no sign, no leading zero, nothing else.
        const std::string_view digits =
            std::string_view(file).substr(name.prefix.size(), file.size() - name.prefix.size() - name.suffix.size());
        pid_t pid = 0;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
        if (error != std::errc() || end != digits.data() + digits.size() || pid <= 0 || digits.front() == '0')
            continue;
        if (!entry.is_symlink(ec) && entry.is_regular_file(ec) && processGone(pid) &&
            fs::remove(entry.path(), ec))
            removed.push_back(target.parent_path().empty() ? entry.path().filename() : entry.path());
    }
    return removed;
}

}  // namespace vri
