#pragma once
// What every tool's main() shares: one-line errors and exit codes.
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "vri/error.h"
#include "vri/printable.h"

namespace vri {

// Exit codes shared by all tools (vri-diff adds its own comparison codes, in the spirit of idiff).
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 64;  // bad argument (CLI11 parse errors use their own code, also non-zero)
inline constexpr int kExitError = 1;   // bad input file, failed computation

// "x,y" -> vector; throws vri::Error naming `what` unless there are exactly two finite numbers.
glm::dvec2 parseVec2(const std::string& text, const std::string& what);
// "x,y,z" -> vector; throws vri::Error naming `what` unless there are exactly three finite numbers.
glm::dvec3 parseVec3(const std::string& text, const std::string& what);
// "x,y,z" -> integer dims; throws vri::Error naming `what` unless all three are integers in [1, 1e9].
glm::ivec3 parseDims(const std::string& text, const std::string& what);
// "lo,hi" -> pair; throws vri::Error naming `what` unless both are finite and hi > lo.
glm::dvec2 parseRange(const std::string& text, const std::string& what);
// "WxH" -> (W, H); throws vri::Error naming `what` unless both are positive integers.
glm::ivec2 parseSize(const std::string& text, const std::string& what);
// "X,Y" -> a pixel; throws vri::Error naming `what` unless both are integers >= 0.
glm::ivec2 parsePixel(const std::string& text, const std::string& what);
// A positive finite number, or "none" -> +infinity (no limit); throws vri::Error naming `what` otherwise.
double parseLimit(const std::string& text, const std::string& what);

// "a,b,c" -> the words between the commas (empty words are an error naming `what`).
std::vector<std::string> parseWordList(const std::string& text, const std::string& what);
// "1,4,16" -> positive finite numbers; throws vri::Error naming `what` otherwise.
std::vector<double> parsePositiveList(const std::string& text, const std::string& what);
// "3,17" -> integers in [0, count); throws vri::Error naming `what` otherwise.
std::vector<int> parseIndexList(const std::string& text, const std::string& what, int count);

// Parses the command line; a usage error becomes the one line "<tool>: error: <what>"
// (exit code CLI11's), --help prints the help (exit 0). Returns the exit code to leave with, if any.
inline std::optional<int> parseArguments(CLI::App& app, std::string_view tool, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << tool << ": error: " << printable(e.what()) << " (see --help)\n";
        return e.get_exit_code();
    }
    return std::nullopt;
}

// The one line for an exception that no check turned into vri::Error (out of memory, a file-system
// or JSON library failure): said in words and naming the path where there is one, not as a library's
// raw text.
std::string describeUnexpected(const std::exception& e);

// Runs body() and turns an escaping exception into the single line "<tool>: error: <what>", its
// control characters escaped (printable.h).
template <class Body>
int guardedMain(std::string_view tool, Body&& body) {
    const auto report = [&](const std::string& what) { std::cerr << tool << ": error: " << printable(what) << '\n'; };
    try {
        return body();
    } catch (const Error& e) {
        report(e.what());
    } catch (const std::exception& e) {
        report(describeUnexpected(e));
    }
    return kExitError;
}

}  // namespace vri
