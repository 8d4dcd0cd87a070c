// The heartbeat of a long call: a line per interval while it runs, nothing when it is short or disabled.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <regex>
#include <string>
#include <thread>

#include "libvri/util/heartbeat.h"

namespace {

using namespace std::chrono_literals;

// What a heartbeat wrote into a temporary file while `work` ran.
template <class Work>
std::string heartbeatOutput(bool enabled, std::chrono::milliseconds interval, Work work) {
    std::FILE* file = std::tmpfile();
    REQUIRE(file != nullptr);
    {
        const vri::Heartbeat heartbeat("beat", enabled, interval, file);
        work();
    }
    std::rewind(file);
    std::string text;
    for (int c; (c = std::fgetc(file)) != EOF;) text += static_cast<char>(c);
    std::fclose(file);
    return text;
}

}  // namespace

TEST_CASE("heartbeat: a line per interval while the call runs, none when it is short or disabled") {
    const auto start = std::chrono::steady_clock::now();
    const std::string beats = heartbeatOutput(true, 40ms, [] { std::this_thread::sleep_for(300ms); });
    const auto elapsed = std::chrono::steady_clock::now() - start;  // a loaded machine oversleeps
    const auto lines = std::count(beats.begin(), beats.end(), '\n');
    CHECK(lines >= 3);  // a beat per interval that passed: at least 3 of the 7, however loaded the machine
    CHECK(lines <= elapsed / 40ms);
    CHECK(std::regex_match(beats, std::regex("(beat: [0-9]+ s\n)+")));
    CHECK(heartbeatOutput(true, 10s, [] { std::this_thread::sleep_for(20ms); }).empty());
    CHECK(heartbeatOutput(false, 10ms, [] { std::this_thread::sleep_for(100ms); }).empty());
}
