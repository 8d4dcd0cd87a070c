// Naming writeAtomically's temporary files, finding them by name and asking the kernel whether their
// writer lives.
#include "libvri/util/stale_temp_files.h"

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <span>
#include <string>
#include <string_view>

#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// ".STEM.tmp." and EXT: what every temporary file of `target` starts and ends with.
struct TemporaryName {
    std::string prefix, suffix;
};

// The longest file name Linux's file systems take (NAME_MAX), and the most digits a pid prints with.
constexpr std::size_t kMaxNameBytes = 255;
constexpr std::size_t kMaxPidDigits = 10;
constexpr std::size_t kHashChars = 16;

TemporaryName temporaryName(const fs::path& target) {
    std::string stem = target.stem().string();
    std::string extension = target.extension().string();
    // ".", ".tmp.", the pid: up to 16 bytes more than the target's name, which a name of 240 to 255 bytes
    // has no room for. Its stem is then cut to fit and followed by "~" and 16 hex digits of the SHA-512 of
    // the whole name, so that two long names alike at the start keep their own temporary files; an
    // extension too long to leave room for them (it names no format vri writes) is dropped as well.
    const auto length = [&] { return 1 + stem.size() + 5 + kMaxPidDigits + extension.size(); };
    if (length() > kMaxNameBytes) {
        const std::string name = target.filename().string();
        const std::string hash =
            "~" + sha512Hex(std::as_bytes(std::span(name.data(), name.size()))).substr(0, kHashChars);
        if (1 + hash.size() + 5 + kMaxPidDigits + extension.size() > kMaxNameBytes) extension.clear();
        std::size_t keep = kMaxNameBytes - (1 + hash.size() + 5 + kMaxPidDigits + extension.size());
        keep = std::min(keep, stem.size());
        // Cut between characters, not inside a UTF-8 sequence (its continuation bytes are 10xxxxxx).
        while (keep > 0 && keep < stem.size() && (static_cast<unsigned char>(stem[keep]) & 0xc0) == 0x80) --keep;
        stem = stem.substr(0, keep) + hash;
    }
    // Appended piece by piece: `"." + std::string` trips a false -Wrestrict in GCC 12.
    std::string prefix = ".";
    prefix += stem;
    prefix += ".tmp.";
    return {prefix, extension};
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
