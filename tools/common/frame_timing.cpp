#include "common/frame_timing.h"

#include <cstdio>
#include <sstream>

#include "libvri/util/statistics.h"

namespace vri {

void FrameTiming::addTo(CLI::App& app) {
    app.add_option("--threads", threads_, "worker threads (default: all cores)");
}

void FrameTiming::limitThreads(std::optional<tbb::global_control>& control) const {
    if (threads_ < 0) throw Error("--threads: expected a positive count, got " + std::to_string(threads_));
    if (threads_ > 0) control.emplace(tbb::global_control::max_allowed_parallelism, threads_);
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

nlohmann::json FrameTiming::toJson(const std::vector<double>& wallSeconds) const {
    return {{"warm_up_frames", warmUp_},
            {"repeats", repeat_},
            {"wall_seconds", wallSeconds},
            {"median_wall_seconds", median(wallSeconds)}};
}

std::string FrameTiming::summary(const std::vector<double>& wallSeconds) const {
    std::ostringstream out;
    out << median(wallSeconds) << " s";
    if (repeat_ > 1) out << " (median of " << repeat_ << ")";
    return out.str();
}

}  // namespace vri
