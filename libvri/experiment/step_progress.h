#pragma once
// What vri-run says while a plan's steps run (README "Progress"). Without a terminal (a log, CI) a plain
// line per started and per finished step, so that a long run shows life line by line; on a terminal the
// finished steps' lines and, redrawn below them, a live line with the steps done, those running and an
// ETA priced from the last manifest's wall times (step_costs.h). Quiet: nothing.
#include <chrono>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"

namespace vri {

class StepProgress {
public:
    enum class Style { Lines, Live, Quiet };

    // `prices`: per step its last wall time, if known (empty: none known); `jobs`: steps run at once.
    StepProgress(const Plan& plan, std::vector<std::optional<double>> prices, int jobs, Style style);
    ~StepProgress();  // clears the live line
    StepProgress(const StepProgress&) = delete;
    StepProgress& operator=(const StepProgress&) = delete;

    // Lines without a terminal, Live on one, Quiet when asked.
    static Style styleFor(bool quiet);

    void started(std::size_t step);
    // `how`: "ran", "cached", "failed", ...; `detail` follows in parentheses ("1.23 s").
    void settled(std::size_t step, const std::string& how, const std::string& detail);

    // What a step's tool warned of, on a line of its own (shown in every style but Quiet's).
    void warning(std::size_t step, const std::string& text);

    // The live line's text: "[done/total] running: a, b; ETA 12.3 s" (public for its test).
    std::string statusText() const;

private:
    using Clock = std::chrono::steady_clock;
    void line(const std::string& text);  // one finished line, the live line redrawn under it
    void redraw();

    const Plan& plan_;
    std::vector<std::optional<double>> prices_;
    int jobs_;
    Style style_;
    Clock::time_point start_;
    std::vector<std::optional<Clock::time_point>> running_;  // per step: when it started, while it runs
    std::vector<bool> settled_;
    std::size_t settledCount_ = 0;
    bool liveShown_ = false;
};

}  // namespace vri
