#include "libvri/util/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vri {

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total), active_(enabled && total > 0), terminal_(::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
    if (!active_ || shown_.load() < 0) return;
    if (terminal_)
        std::fprintf(stderr, "\r%s: done        \n", label_.c_str());
    else
        std::fprintf(stderr, "%s - done\n", shown_.load() < 10 ? "...100" : "");
}

void Progress::advance(std::uint64_t n) {
    if (!active_) return;
    const std::uint64_t done = done_.fetch_add(n) + n;
    const int percent = static_cast<int>(100 * done / total_);
    const int level = terminal_ ? percent : percent / 10;
    if (level <= shown_.load()) return;
    if (!terminal_ &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() < kSilentSeconds)
        return;
    const std::lock_guard<std::mutex> lock(print_);
    const int shown = shown_.load();
    if (level <= shown) return;  // another thread printed it meanwhile
    if (terminal_) {
        std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), percent);
    } else {
        if (shown < 0) std::fprintf(stderr, "%s: 0", label_.c_str());
        for (int tens = std::max(shown, 0) + 1; tens <= level; ++tens) std::fprintf(stderr, "...%d", 10 * tens);
    }
    std::fflush(stderr);
    shown_.store(level);
}

}  // namespace vri
