#include "common/frame_timing.h"

#include <sstream>

#include "vri/util/statistics.h"

namespace vri {

void FrameTiming::addTo(CLI::App& app) {
    app.add_option("--threads", threads_, "worker threads (default: all cores)");
    app.add_option("--warm-up", warmUp_, "render N untimed frames first (caches, clocks, a GPU's pipelines)")
        ->capture_default_str();
    app.add_option("--repeat", repeat_, "render N times for timing: the stats give every wall time and their median, "
                                        "and any image that differs from the first is an error")
        ->capture_default_str();
}

void FrameTiming::limitThreads(std::optional<tbb::global_control>& control) const {
    if (threads_ < 0) throw Error("--threads: expected a positive count, got " + std::to_string(threads_));
    if (repeat_ < 1) throw Error("--repeat: expected a positive count, got " + std::to_string(repeat_));
    if (warmUp_ < 0) throw Error("--warm-up: expected a count >= 0, got " + std::to_string(warmUp_));
    if (threads_ > 0) control.emplace(tbb::global_control::max_allowed_parallelism, threads_);
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
