#include "common/frame_timing.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "libvri/util/statistics.h"

namespace vri {

void FrameTiming::addTo(CLI::App& app) {
    app.add_option("--threads", threads_,
                   "worker threads (default, and 0: all cores; more than the cores run on all of them, with a warning)");
}

void FrameTiming::limitThreads(std::optional<tbb::global_control>& control, std::string_view tool) const {
    if (threads_ < 0) throw Error("--threads: expected 0 (all cores) or a positive count, got " + std::to_string(threads_));
    if (threads_ == 0) return;
    // The cores this process may use (its CPU affinity included): oneTBB runs no more workers, and a larger
    // limit would only cost memory (2^31 - 1 of them ran out of it).
    const int cores = tbb::info::default_concurrency();
    control.emplace(tbb::global_control::max_allowed_parallelism, std::min(threads_, cores));
    if (threads_ > cores)
        std::cerr << tool << ": warning: --threads " << threads_ << ": more than the " << cores
                  << (cores == 1 ? " core" : " cores") << " this process may use; at most " << cores << " run\n";
}

void FrameTiming::setFrames(int warmUp, int repeat, std::string tool, bool quiet) {
    warmUp_ = warmUp;
    repeat_ = repeat;
    tool_ = std::move(tool);
    quiet_ = quiet;
}

void FrameTiming::report(const char* what, int index, int count, double seconds) const {
    if (quiet_ || warmUp_ + repeat_ < 2) return;
    std::fprintf(stderr, "%s: %s %d of %d: %.3g s\n", tool_.c_str(), what, index + 1, count, seconds);
}

void FrameTiming::measureLoad(const std::optional<CpuSample>& before) const {
    load_.reset();
    const std::optional<CpuSample> after = sampleCpu();
    if (!before || !after) return;
    const std::optional<double> others = otherProcessCores(*before, *after);
    if (!others) return;
    const int cores = onlineCores(), usable = tbb::info::default_concurrency();
    load_ = TimingLoad{*others, threads_ == 0 ? usable : std::min(threads_, usable), cores};
    if (load_->overloaded() && !quiet_) {  // quiet (as under vri-run), the stats record it and vri-run says it
        char text[64];
        std::snprintf(text, sizeof text, "%.1f", load_->otherCores);
        std::cerr << tool_ << ": warning: the timed frames ran while other processes used " << text << " cores beside "
                  << load_->threads << (load_->threads == 1 ? " thread" : " threads") << " on " << cores
                  << " cores: their times are inflated (timing.load in the stats)\n";
    }
}

nlohmann::json FrameTiming::toJson(const std::vector<double>& wallSeconds) const {
    return frameTimingRecord(warmUp_, wallSeconds, load_);
}

std::string FrameTiming::summary(const std::vector<double>& wallSeconds) const {
    std::ostringstream out;
    out << median(wallSeconds) << " s";
    if (repeat_ > 1) out << " (median of " << repeat_ << ")";
    return out.str();
}

}  // namespace vri
