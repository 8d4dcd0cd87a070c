#include "libvri/util/heartbeat.h"

namespace vri {

Heartbeat::Heartbeat(std::string label, bool enabled, std::chrono::milliseconds interval, std::FILE* out)
    : label_(std::move(label)), interval_(interval), out_(out) {
    if (enabled) thread_ = std::thread([this] { beat(); });
}

Heartbeat::~Heartbeat() {
    if (!thread_.joinable()) return;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

void Heartbeat::beat() {
    const auto start = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    for (auto next = start + interval_; !wake_.wait_until(lock, next, [this] { return stop_; }); next += interval_) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(out_, "%s: %.0f s\n", label_.c_str(), seconds);
        std::fflush(out_);
    }
}

}  // namespace vri
