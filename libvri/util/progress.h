#pragma once
// Progress of long work on stderr, safe to advance from many threads. On a terminal a percentage
// redrawn in place; without one (a log, CI), once the work has lasted kSilentSeconds, one line growing
// by tens as GDAL's "0...10...20...100 - done", so that a log shows life without a line per tile.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace vri {

class Progress {
public:
    // Work shorter than this says nothing without a terminal: the tools' many small renders stay quiet.
    static constexpr double kSilentSeconds = 1.0;

    // `enabled` is a request (the tools' -q clears it).
    Progress(std::string label, std::uint64_t total, bool enabled);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(std::uint64_t n);

private:
    std::string label_;
    std::uint64_t total_;
    bool active_, terminal_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<std::uint64_t> done_{0};
    std::atomic<int> shown_{-1};  // the percentage (terminal) or tens (log) printed last
    std::mutex print_;            // one printer at a time, so that what is shown only grows
};

}  // namespace vri
