// Child processes: argv reaches the program word for word (no shell), redirections, exit statuses.
#include <doctest/doctest.h>

#include <signal.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "temp_dir.h"
#include "libvri/util/error.h"
#include "libvri/util/process.h"

using namespace vri;

TEST_CASE("process: PATH lookup without a shell") {
    REQUIRE(findProgram("printf"));
    CHECK(findProgram("printf")->is_absolute());
    CHECK(commandAvailable("printf"));
    CHECK_FALSE(commandAvailable("vri-no-such-program"));
    CHECK_FALSE(commandAvailable("printf; touch x"));  // a name is a file name, never a command line
    CHECK_FALSE(commandAvailable(""));
    CHECK(findProgram("/bin/sh") == std::filesystem::path("/bin/sh"));
    CHECK_FALSE(findProgram("/etc/passwd"));  // not executable
}

TEST_CASE("process: every word reaches the program as it is") {
    test::TempDir dir("process");
    const auto printf = findProgram("printf");
    REQUIRE(printf);
    const std::string hostile =
        "$(touch " + (dir / "m1").string() + ") `touch " + (dir / "m2").string() + "` ';touch m3;' \"\n*";
    const auto [status, output] = captureProcess(*printf, {"printf", "[%s]", hostile, ""});
    CHECK(status.ok());
    CHECK(output == "[" + hostile + "][]");
    CHECK_FALSE(std::filesystem::exists(dir / "m1"));
    CHECK_FALSE(std::filesystem::exists(dir / "m2"));
}

TEST_CASE("process: redirections and exit statuses") {
    test::TempDir dir("process");
    const auto printf = findProgram("printf");
    REQUIRE(printf);
    const ExitStatus written =
        runProcess(*printf, {"printf", "out"}, {.in = {}, .out = dir / "o.txt", .err = {}, .errToOut = false});
    CHECK(written.ok());
    std::ostringstream text;
    text << std::ifstream(dir / "o.txt").rdbuf();
    CHECK(text.str() == "out");

    const auto falseProgram = findProgram("false");
    REQUIRE(falseProgram);
    const ExitStatus failed = runProcess(*falseProgram, {"false"});
    CHECK_FALSE(failed.ok());
    CHECK(failed.describe() == "exit status 1");

    const auto sleep = findProgram("sleep");
    REQUIRE(sleep);
    const pid_t pid = startProcess(*sleep, {"sleep", "30"});
    ::kill(pid, SIGKILL);
    const ExitStatus killed = waitProcess(pid);
    CHECK_FALSE(killed.ok());
    CHECK(killed.describe() == "signal 9");

    CHECK_THROWS_WITH_AS(startProcess(dir / "missing", {"missing"}), doctest::Contains("cannot start"), Error);
    CHECK_THROWS_AS(
        startProcess(*printf, {"printf"}, {.in = dir / "no-such-input", .out = {}, .err = {}, .errToOut = false}),
        Error);
}

TEST_CASE("process: a child's peak resident memory comes back with its status") {
    // The small child's peak is at least this process's (process.h): under ctest each case runs alone, small.
    const auto python = findProgram("python3");
    REQUIRE(python);
    // 64 MiB touched (bytearray zero-fills it): the peak holds it, and the interpreter besides.
    const std::vector<std::string> allocate{"python3", "-c", "b = bytearray(64 << 20)"};
    const ExitStatus big = runProcess(*python, allocate);
    CHECK(big.ok());
    CHECK(big.peakRssKiB >= 64 * 1024);
    const ExitStatus small = runProcess(*python, {"python3", "-c", "pass"});
    CHECK(small.peakRssKiB > 0);
    CHECK(small.peakRssKiB < big.peakRssKiB - 32 * 1024);
    // The same through the waits that poll: within a time limit, and any child.
    bool timedOut = true;
    CHECK(runProcessWithin(*python, allocate, 60, timedOut).peakRssKiB >= 64 * 1024);
    CHECK_FALSE(timedOut);
    const pid_t pid = startProcess(*python, allocate);
    std::pair<pid_t, ExitStatus> reaped;
    do reaped = waitAnyProcess();  // a child another test left would come first: passed over
    while (reaped.first != pid);
    CHECK(reaped.second.peakRssKiB >= 64 * 1024);
}

TEST_CASE("process: a captured program is stopped at its time and size limits, and by a signal flag") {
    using Clock = std::chrono::steady_clock;
    const auto seconds = [](Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); };
    // A program that never answers: stopped after the limit (SIGTERM), well before it would end.
    auto start = Clock::now();
    CHECK_THROWS_WITH_AS(vri::captureProcess("/bin/sleep", {"sleep", "60"}, {}, vri::CaptureLimits{0.3, 0, nullptr}),
                         "sleep: no answer within 0.3 s", vri::Error);
    CHECK(seconds(start) < 10);
    // One that closes its output and goes on: waited for within the same limit.
    start = Clock::now();
    CHECK_THROWS_WITH_AS(vri::captureProcess("/bin/sh", {"sh", "-c", "exec >&- 2>&-; sleep 60"}, {},
                                             vri::CaptureLimits{0.3, 0, nullptr}),
                         "sh: no answer within 0.3 s", vri::Error);
    CHECK(seconds(start) < 10);
    // Output without end.
    CHECK_THROWS_WITH_AS(vri::captureProcess("/usr/bin/yes", {"yes"}, {}, vri::CaptureLimits{0, 1 << 20, nullptr}),
                         "yes: printed more than 1048576 bytes", vri::Error);
    // A signal flag already set: stopped at once.
    volatile std::sig_atomic_t stop = SIGTERM;
    start = Clock::now();
    CHECK_THROWS_WITH_AS(vri::captureProcess("/bin/sleep", {"sleep", "60"}, {}, vri::CaptureLimits{0, 0, &stop}),
                         "sleep: stopped by a signal while it ran", vri::Error);
    CHECK(seconds(start) < 10);
    // Within the limits: as captureProcess.
    const auto [status, output] =
        vri::captureProcess("/bin/echo", {"echo", "hello"}, {}, vri::CaptureLimits{30, 1 << 20, nullptr});
    CHECK(status.ok());
    CHECK(output == "hello\n");
}
