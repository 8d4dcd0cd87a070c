// vri-run's progress: a line per step without a terminal, a live line with an ETA on one.
#include "libvri/experiment/step_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "libvri/experiment/step_costs.h"

namespace vri {

StepProgress::StepProgress(const Plan& plan, std::vector<std::optional<double>> prices, int jobs, Style style)
    : plan_(plan), prices_(std::move(prices)), jobs_(std::max(jobs, 1)), style_(style), start_(Clock::now()),
      running_(plan.steps.size()), settled_(plan.steps.size(), false) {
    prices_.resize(plan.steps.size());
}

StepProgress::~StepProgress() {
    if (liveShown_) std::fputs("\r\x1b[K", stderr);
}

StepProgress::Style StepProgress::styleFor(bool quiet) {
    if (quiet) return Style::Quiet;
    return ::isatty(STDERR_FILENO) ? Style::Live : Style::Lines;
}

void StepProgress::started(std::size_t step) {
    running_[step] = Clock::now();
    if (style_ == Style::Lines)
        line("start " + plan_.steps[step].tool + " " + plan_.steps[step].id);
    else if (style_ == Style::Live)
        redraw();
}

void StepProgress::settled(std::size_t step, const std::string& how, const std::string& detail) {
    running_[step].reset();
    settled_[step] = true;
    ++settledCount_;
    if (style_ == Style::Quiet) return;
    line(how + " " + plan_.steps[step].tool + " " + plan_.steps[step].id + (detail.empty() ? "" : " (" + detail + ")"));
}

std::string StepProgress::statusText() const {
    const auto now = Clock::now();
    double seconds = 0;
    std::size_t unpriced = 0;
    std::vector<std::string> running;
    for (std::size_t i = 0; i < settled_.size(); ++i) {
        if (settled_[i]) continue;
        if (running_[i]) running.push_back(plan_.steps[i].id);
        if (!prices_[i]) {
            ++unpriced;
            continue;
        }
        const double elapsed = running_[i] ? std::chrono::duration<double>(now - *running_[i]).count() : 0.0;
        seconds += std::max(0.0, *prices_[i] - elapsed);
    }
    std::string text = "[" + std::to_string(settledCount_) + "/" + std::to_string(settled_.size()) + "]";
    if (!running.empty()) {
        text += " running: ";
        constexpr std::size_t kNamed = 3;  // more would not fit a terminal's line
        for (std::size_t k = 0; k < std::min(running.size(), kNamed); ++k) text += (k ? ", " : "") + running[k];
        if (running.size() > kNamed) text += " and " + std::to_string(running.size() - kNamed) + " more";
        text += ";";
    }
    // The steps' last wall times shared among the jobs that run at once: an estimate, as `make estimate`'s.
    if (unpriced == 0)
        text += " ETA " + secondsText(seconds / jobs_);
    else if (seconds > 0)
        text += " ETA at least " + secondsText(seconds / jobs_) + " (" + std::to_string(unpriced) + " steps unpriced)";
    else
        text += " no ETA (" + std::to_string(unpriced) + " steps never ran)";
    return text;
}

void StepProgress::warning(std::size_t step, const std::string& text) {
    if (style_ != Style::Quiet) line(plan_.steps[step].id + ": " + text);
}

void StepProgress::line(const std::string& text) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    std::fprintf(stderr, "%svri-run: %s [%zu/%zu] %.1f s: %s\n", liveShown_ ? "\r\x1b[K" : "",
                 plan_.resultsDir.filename().c_str(), settledCount_, settled_.size(), elapsed, text.c_str());
    liveShown_ = false;
    if (style_ == Style::Live) redraw();
}

void StepProgress::redraw() {
    if (settledCount_ == settled_.size()) {  // nothing left to estimate: the summary line follows
        if (liveShown_) std::fputs("\r\x1b[K", stderr);
        liveShown_ = false;
        return;
    }
    std::fprintf(stderr, "\r\x1b[Kvri-run: %s %s", plan_.resultsDir.filename().c_str(), statusText().c_str());
    std::fflush(stderr);
    liveShown_ = true;
}

}  // namespace vri
