#pragma once
// What every tool's main() shares: one-line errors and exit codes.
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "vri/util/error.h"
#include "vri/util/parse.h"
#include "vri/util/printable.h"

namespace vri {

// Exit codes shared by all tools (vri-diff adds its own comparison codes, in the spirit of idiff).
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 64;  // bad argument (CLI11 parse errors use their own code, also non-zero)
inline constexpr int kExitError = 1;   // bad input file, failed computation

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

// The files a tool writes, each with the option that named it ("-o", "--png", ...).
struct OutputArgument {
    std::string option;
    std::string path;  // empty: not asked for; "-": standard output
};
// Throws UsageError "<option>: '<path>' is not an .exr file (...)" unless the path ends in .exr
// (any case): the float RGBA image is written as OpenEXR whatever the name says.
void requireExrOutput(const OutputArgument& output);
// Throws UsageError "<option>: '<path>' is also <other option>'s output" when two outputs name one
// file, however spelled (./x, a/../x, a symbolic link or a hard link to it): the later write would
// replace the earlier one.
void requireDistinctOutputs(const std::vector<OutputArgument>& outputs);

// The one line for an exception that no check turned into vri::Error (out of memory, a file-system
// or JSON library failure): said in words and naming the path where there is one, not as a library's
// raw text.
std::string describeUnexpected(const std::exception& e);

// Runs body() and turns an escaping exception into the single line "<tool>: error: <what>", its
// control characters escaped (printable.h); exit kExitUsage for a UsageError, kExitError otherwise.
// What body() printed must have reached stdout: a full disk behind a redirection is a failure too.
template <class Body>
int guardedMain(std::string_view tool, Body&& body) {
    const auto report = [&](const std::string& what) { std::cerr << tool << ": error: " << printable(what) << '\n'; };
    try {
        const int code = body();
        if (!std::cout.flush()) throw Error("stdout: cannot write what was printed (disk full or output closed?)");
        return code;
    } catch (const UsageError& e) {
        report(e.what());
        return kExitUsage;
    } catch (const Error& e) {
        report(e.what());
    } catch (const std::exception& e) {
        report(describeUnexpected(e));
    }
    return kExitError;
}

}  // namespace vri
