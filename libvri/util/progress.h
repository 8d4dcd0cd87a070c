#pragma once
// Progress of long work on stderr, only when stderr is a terminal, safe to advance from many threads.
#include <atomic>
#include <cstdint>
#include <string>

namespace vri {

class Progress {
public:
    // `enabled` is a request; the reporter also stays quiet unless stderr is a terminal.
    Progress(std::string label, std::uint64_t total, bool enabled);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(std::uint64_t n);

private:
    std::string label_;
    std::uint64_t total_;
    bool active_;
    std::atomic<std::uint64_t> done_{0};
    std::atomic<int> shownPercent_{-1};
};

}  // namespace vri
