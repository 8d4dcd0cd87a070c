#pragma once
// Life shown during one long call whose fraction done nobody reports (OpenVDB copying a dense volume
// into a grid and writing it, a whole file inflated): Progress (progress.h) needs a count, this only
// the time. Every `interval` while the call runs it prints "<label>: <N> s" as a line of its own, so a
// log or CI sees the work go on; a call shorter than one interval says nothing.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace vri {

class Heartbeat {
public:
    static constexpr std::chrono::milliseconds kInterval{5000};

    // `enabled` is a request (the tools' -q clears it); the lines go to `out`.
    Heartbeat(std::string label, bool enabled, std::chrono::milliseconds interval = kInterval, std::FILE* out = stderr);
    ~Heartbeat();  // stops the beat before returning
    Heartbeat(const Heartbeat&) = delete;
    Heartbeat& operator=(const Heartbeat&) = delete;

private:
    void beat();

    std::string label_;
    std::chrono::milliseconds interval_;
    std::FILE* out_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace vri
