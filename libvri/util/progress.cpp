#include "libvri/util/progress.h"

#include <unistd.h>

#include <cstdio>

namespace vri {

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total), active_(enabled && total > 0 && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() {
    if (active_ && shownPercent_.load() >= 0) std::fprintf(stderr, "\r%s: done        \n", label_.c_str());
}

void Progress::advance(std::uint64_t n) {
    if (!active_) return;
    const std::uint64_t done = done_.fetch_add(n) + n;
    const int percent = static_cast<int>(100 * done / total_);
    int shown = shownPercent_.load();
    // Only the thread that moves the shown percentage prints, so lines do not interleave.
    while (percent > shown) {
        if (shownPercent_.compare_exchange_weak(shown, percent)) {
            std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), percent);
            std::fflush(stderr);
            break;
        }
    }
}

}  // namespace vri
