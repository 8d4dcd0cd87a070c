#pragma once
// What every tool's main() shares: one-line errors and exit codes.
#include <cstdint>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "libvri/util/error.h"
#include "libvri/util/parse.h"
#include "libvri/util/printable.h"

namespace vri {

// Exit codes shared by all tools (README, "Exit codes"); vri-diff's comparison verdicts add 2 to 4.
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;   // bad input file, failed computation
// A command line CLI11 refuses (unknown, missing or unconvertible option, options that exclude each
// other) or a UsageError; BSD's EX_USAGE.
inline constexpr int kExitUsage = 64;
// vri-verify: a finding of the report failed, as vri-diff's fail verdict (3).
inline constexpr int kExitVerifyFailed = 3;

// What --version prints: "<tool> (vri) <version>" and a line with the git commit at configure time,
// the build type, the compiler and whether the Vulkan backend is built.
std::string versionText(std::string_view tool);

// Checks on a number option's value with vri's messages, in place of CLI11's Range, PositiveNumber and
// NonNegativeNumber (whose messages read "Value 100 not in range 1 to 64" and print doubles in full):
// "expected a whole number from 1 to 64, got '100'", "expected a number > 0, got '0'" (finite, as parsePositive
// takes it). parseArguments has checked that the text is a number before these run.
CLI::Validator integerRange(std::int64_t lo, std::int64_t hi);
CLI::Validator numberRange(double lo, double hi);
CLI::Validator numberAbove(double lo, bool orEqual);

// A volume file option's lookup, as experiment files and Python make it: a relative name that is no file here
// becomes that file in the data directory ($VRI_DATA_DIR, io/volume_lookup.h) when it is there; else the
// value stays as given, and reading it says what is missing.
CLI::Validator volumeInDataDir();

// A list option ("--threshold 0.1,0.2"): one word a use, as typed (brackets too), split into items at single
// commas by parseWordList, which refuses an empty item; the items of every use, in order, replace the default.
// A number list reads each item as a number option's value is read (parse.h) and checks it with `check`;
// `count`, when not 0, is the number of items the option must have, given once. vri splits the word, not CLI11, whose list
// parsing drops empty items.
CLI::Option* addListOption(CLI::App& app, const std::string& name, std::vector<double>& items,
                           const std::string& description, std::optional<CLI::Validator> check = std::nullopt,
                           std::size_t count = 0);
CLI::Option* addListOption(CLI::App& app, const std::string& name, std::vector<std::string>& items,
                           const std::string& description);

// An option of several words a use ("--cell ROW COLUMN FILE..."), `usage` naming them: from `least` to `most`
// words, the first whatever it looks like and the others up to the next option; each use's words as typed,
// one entry of `uses` a use. An empty word, which CLI11 would take for a break between uses, is refused.
CLI::Option* addWordsOption(CLI::App& app, const std::string& name, std::vector<std::vector<std::string>>& uses,
                            const std::string& usage, int least, int most, const std::string& description);

// Parses the command line, after adding --version; a usage error becomes the one line
// "<tool>: error: <what> (see --help)" and exit kExitUsage, --help and --version print on stdout
// (exit 0). Returns the exit code to leave with, if any. Every number option's text is checked first in
// parse.h's forms, and "--name=" with nothing after '=' is refused (CLI11 would take the next word).
std::optional<int> parseArguments(CLI::App& app, std::string_view tool, int argc, char** argv);

// Throws UsageError "argument N '<arg>' is not valid UTF-8 (byte B): <why>" for the first argument that is
// not: a tool whose JSON output holds its arguments checks before any work, since that output, written last,
// could not hold them. `why` says what JSON would hold them.
inline constexpr std::string_view kJsonKeepsCommandLine = "the JSON record keeps the command line, and JSON holds UTF-8 text only";
void requireUtf8Arguments(int argc, char** argv, std::string_view why = kJsonKeepsCommandLine);

// The files a tool writes, each with the option that named it ("-o", "--png", ...).
struct OutputArgument {
    std::string option;
    std::string path;  // empty: not asked for; "-": standard output
};
// Throws UsageError "<option>: '<path>' is not an .exr file (...)" unless the path ends in .exr
// (any case): the float RGBA image is written as OpenEXR whatever the name says.
void requireExrOutput(const OutputArgument& output);
// Throws Error "<option>: <path>: cannot write: ..." for an output that no write could replace (a
// directory, a socket, ...), and UsageError "<option>: '<path>' is also <other option>'s output" when two
// outputs name one file, however spelled (./x, a/../x, a symbolic link, dangling or not, or a hard link
// to it): the later write would replace the earlier one. Called before any work, so that nothing is
// written when one output is wrong.
void requireDistinctOutputs(const std::vector<OutputArgument>& outputs);

// The files a tool reads, each with the option (or positional name) that named it.
struct InputArgument {
    std::string option;
    std::string path;  // empty: not given; "-": standard input
};
// A volume file as the files reading it opens: the file, and the data file its header names (labelled
// "<option>'s data file").
std::vector<InputArgument> volumeInputArguments(const std::string& option, const std::string& path);
// Throws UsageError "<output option> '<path>' is the same file as <input option> '<path>'" when an output
// names an existing regular file that is one of the inputs (same device and inode: through any spelling,
// symbolic or hard link), since writing it would destroy what is being read; an output that does not
// exist yet names no input. Called with every option before any work, so that nothing is written.
void requireOutputsApartFromInputs(const std::vector<OutputArgument>& outputs,
                                   const std::vector<InputArgument>& inputs);

// The one line for an exception that no check turned into vri::Error (out of memory, a file-system
// or JSON library failure): said in words and naming the path where there is one, not as a library's
// raw text.
std::string describeUnexpected(const std::exception& e);

// Keeps the memory a tool frees for its next allocation: a tool is a short process that allocates and frees
// image-sized buffers over and over (vri-diff's SSIM and FLIP planes), which glibc's defaults hand back to the
// kernel and fault in again (vri-diff on 800x600 images: 0.42 s -> 0.33 s). Called by guardedMain.
void retainFreedMemory();

// Runs body() and turns an escaping exception into the single line "<tool>: error: <what>", its
// control characters escaped (printable.h; a DetailedError keeps its lines); exit kExitUsage for a UsageError, kExitError otherwise.
// What body() printed must have reached stdout: a full disk behind a redirection is a failure too.
template <class Body>
int guardedMain(std::string_view tool, Body&& body) {
    const auto report = [&](const std::string& what) {
        std::cerr << tool << ": error: " << printableShort(what, kMaxMessageBytes) << '\n';
    };
    retainFreedMemory();
    try {
        const int code = body();
        if (!std::cout.flush()) throw Error("stdout: cannot write what was printed (disk full or output closed?)");
        return code;
    } catch (const UsageError& e) {
        report(e.what());
        return kExitUsage;
    } catch (const DetailedError& e) {
        std::cerr << tool << ": error: " << printableLines(e.what()) << '\n';
    } catch (const Error& e) {
        report(e.what());
    } catch (const std::exception& e) {
        report(describeUnexpected(e));
    }
    return kExitError;
}

}  // namespace vri
