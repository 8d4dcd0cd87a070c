#include "common/cli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/io/provenance.h"
#include "libvri/io/volume_io.h"
#include "libvri/io/volume_lookup.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/format.h"
#include "libvri/util/json_file.h"
#include "libvri/util/same_file.h"
#include "libvri/util/utf8.h"

namespace vri {

namespace {

namespace fs = std::filesystem;

// The file a write of the path replaces: a symbolic link's final target (dangling or not), absolute,
// '.' and '..' resolved, and every symbolic link in the part that exists followed, so that two
// spellings of one file compare equal.
fs::path fileIdentity(const std::string& path) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(outputTarget(path), ec);
    if (ec) return fs::path(path).lexically_normal();
    const fs::path resolved = fs::weakly_canonical(absolute, ec);
    return ec ? absolute.lexically_normal() : resolved;
}

// What a number option holds, from CLI11's name for its type ("INT", "UINT" or "FLOAT", before any ":" and the
// validators' descriptions); nullopt for any other option.
enum class NumberKind { Integer, NonNegativeInteger, Real };
std::optional<NumberKind> numberKind(const CLI::Option& option) {
    std::string type = option.get_type_name();
    type = type.substr(0, type.find(':'));
    if (type == "INT") return NumberKind::Integer;
    if (type == "UINT") return NumberKind::NonNegativeInteger;
    if (type == "FLOAT") return NumberKind::Real;
    return std::nullopt;
}

// The double in C's hexadecimal form ("-0x1.8p+1"), which reads back exactly.
std::string hexadecimalText(double value) {
    char digits[40];
    const auto end = std::to_chars(digits, digits + sizeof digits, std::fabs(value), std::chars_format::hex).ptr;
    return (std::signbit(value) ? "-0x" : "0x") + std::string(digits, end);
}

// A number option's text checked before CLI11 converts it, in parse.h's forms, so that these options read numbers
// as every other one does: CLI11 alone skips leading spaces, reads an empty value as 0, a leading 0 as octal
// (010 is 8) and clamps what overflows 64 bits. An integer goes on to CLI11 as its decimal digits; what fits in
// 64 bits but not in the option's type is a ConversionError (conversionMessage).
CLI::Validator numberText(NumberKind kind) {
    return CLI::Validator(
        [kind](std::string& value) -> std::string {
            if (kind == NumberKind::Real) {
                const auto number = numberFromText(value);
                if (!number) return "expected a number, got '" + value + "'";
                // CLI11 reads through long double (strtold), which can round a long decimal twice; where that
                // misses the nearest double, CLI11 gets the value in hexadecimal, which both read exactly.
                if (!std::isnan(*number) && static_cast<double>(std::strtold(value.c_str(), nullptr)) != *number)
                    value = hexadecimalText(*number);
                return "";
            }
            bool outOfRange = false;
            const auto integer = integerFromText(value, &outOfRange);
            if (!integer)
                return outOfRange ? value + " is outside the range of this integer option"
                                  : "expected an integer (decimal, or hexadecimal after 0x), got '" + value + "'";
            if (kind == NumberKind::NonNegativeInteger && *integer < 0)
                return "expected an integer >= 0, got '" + value + "'";
            value = std::to_string(*integer);
            return "";
        },
        "", "number text");
}

// Gives every number option of the app and of its option groups numberText, ahead of its other validators.
void checkNumberText(CLI::App& app) {
    for (CLI::Option* option : app.get_options())
        if (const auto kind = numberKind(*option)) option->transform(numberText(*kind));
    for (CLI::App* group : app.get_subcommands({})) checkNumberText(*group);
}

// CLI11's "Could not convert: --warm-up = 2147483648", once numberText has passed the text, is an integer
// outside the option's type: said so. A message of another form stays as it is.
std::string conversionMessage(const CLI::App& app, const std::string& what) {
    constexpr std::string_view prefix = "Could not convert: ";
    const std::size_t equals = what.find(" = ");
    if (what.rfind(prefix, 0) != 0 || equals == std::string::npos) return what;
    const std::string name = what.substr(prefix.size(), equals - prefix.size());
    const CLI::Option* option = app.get_option_no_throw(name);
    if (!option || !numberKind(*option) || numberKind(*option) == NumberKind::Real) return what;
    return name + ": " + what.substr(equals + 3) + " is outside the range of this integer option";
}

// A list option ("--threshold 0.1,0.2", items split at its delimiter) or an option of several words a use ("--cell
// ROW COLUMN FILE..."). CLI11 would read a word in brackets given to one ("[a,b]") as a list of its own; with
// extra arguments off it takes each word as typed, and a list option one word a use, so that the words after it
// are the command's other arguments (vri-diff --threshold 0.1 a.exr b.exr --json d.json).
bool isWordList(const CLI::Option& option) {
    return option.get_delimiter() != '\0' || option.get_type_size_max() > 1;
}
void takeWordsAsTyped(CLI::App& app) {
    for (CLI::Option* option : app.get_options())
        if (isWordList(*option)) option->allow_extra_args(false);
    for (CLI::App* group : app.get_subcommands({})) takeWordsAsTyped(*group);
}

// What CLI11 takes a word for, once an option has its least number of words (App::_recognize): "--" ends the
// options; '-' and a character that can begin a name starts an option, but for '-' and a digit where no option is
// so named (-1,,1 is a value); anything else is a value.
enum class WordKind { Value, Option, EndOfOptions };
WordKind wordKind(const CLI::App& app, std::string_view word) {
    if (word == "--") return WordKind::EndOfOptions;
    if (word.size() < 2 || word[0] != '-') return WordKind::Value;
    const bool longName = word[1] == '-';
    const char first = longName ? (word.size() > 2 ? word[2] : ' ') : word[1];
    if (first == '-' || first == '!' || first == ' ' || first == '\n') return WordKind::Value;
    if (!longName && std::isdigit(static_cast<unsigned char>(first)) && !app.get_option_no_throw(std::string{'-', first}))
        return WordKind::Value;
    return WordKind::Option;
}

// An empty value a word list's option would lose: CLI11 drops an empty item of a list ("0.1,,0.2" is two
// thresholds, "a," one word; vri's lists are comma-separated, as parseWordList reads them) and takes an empty word
// for its break between two uses of an option of several words (--cell A '' f.json would lose its column).
void refuseEmptyValue(const CLI::Option& option, std::string_view word) {
    if (option.get_delimiter() == '\0') {
        if (word.empty()) throw CLI::ValidationError(option.get_name(), "an empty word cannot be one of its values");
        return;
    }
    try {
        parseWordList(std::string(word), option.get_name());
    } catch (const Error& e) {
        throw CLI::ValidationError(e.what());
    }
}

// Refuses, before CLI11 reads them, the empty values a word list's option would lose. The words an option takes
// are found as CLI11 finds them (App::_parse_arg): its value after '=', then its least number of words whatever
// they look like, then, up to its most, the words that are values; a "--" that ends such a run is CLI11's too.
void refuseEmptyValues(const CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view word = argv[i];
        const WordKind kind = wordKind(app, word);
        if (kind == WordKind::EndOfOptions) return;
        if (kind == WordKind::Value) continue;
        const std::size_t equals = word.starts_with("--") ? word.find('=') : std::string_view::npos;
        const CLI::Option* option = app.get_option_no_throw(std::string(word.substr(0, equals)));
        if (!option || option->get_items_expected_max() == 0) continue;  // unknown (CLI11 says so), or a flag
        const auto take = [&](std::string_view value) {
            if (isWordList(*option)) refuseEmptyValue(*option, value);
        };
        const int least = std::min(option->get_type_size_min(), option->get_items_expected_min());
        const bool extra = option->get_allow_extra_args();
        std::int64_t most = option->get_items_expected_max();
        if (!extra && most >= CLI::detail::expected_max_vector_size / 16)
            most = std::int64_t{option->get_type_size_max()} * option->get_expected_min();
        int taken = 0;
        if (equals != std::string_view::npos) {
            take(word.substr(equals + 1));
            taken = 1;
        }
        for (; taken < least && i + 1 < argc; ++taken) take(argv[++i]);
        if (taken >= most && !extra) continue;
        for (; (taken < most || extra) && i + 1 < argc && wordKind(app, argv[i + 1]) == WordKind::Value; ++taken)
            take(argv[++i]);
        if (i + 1 < argc && wordKind(app, argv[i + 1]) == WordKind::EndOfOptions) ++i;
    }
}

}  // namespace

CLI::Validator integerRange(std::int64_t lo, std::int64_t hi) {
    const std::string range = std::to_string(lo) + " to " + std::to_string(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& value) -> std::string {
            const auto v = integerFromText(value);
            return v && *v >= lo && *v <= hi ? "" : "expected a whole number from " + range + ", got '" + value + "'";
        },
        "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", "integer range");
}

CLI::Validator numberRange(double lo, double hi) {
    const std::string range = exactNumber(lo) + " to " + exactNumber(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& value) -> std::string {
            const auto v = numberFromText(value);
            return v && *v >= lo && *v <= hi ? "" : "expected a number from " + range + ", got '" + value + "'";
        },
        "in [" + exactNumber(lo) + ", " + exactNumber(hi) + "]", "number range");
}

CLI::Validator numberAbove(double lo, bool orEqual) {
    const std::string bound = (orEqual ? ">= " : "> ") + exactNumber(lo);
    return CLI::Validator(
        [lo, orEqual, bound](std::string& value) -> std::string {
            const auto v = numberFromText(value);
            return v && std::isfinite(*v) && (*v > lo || (orEqual && *v == lo))
                       ? ""
                       : "expected a number " + bound + ", got '" + value + "'";
        },
        bound, "lower bound");
}

CLI::Validator volumeInDataDir() {
    return CLI::Validator(
        [](std::string& value) -> std::string {
            std::error_code ec;
            if (value.empty() || std::filesystem::exists(std::filesystem::symlink_status(value, ec))) return "";
            if (const std::optional<std::filesystem::path> found = findVolume(value, ".")) value = found->string();
            return "";
        },
        "", "volume in $VRI_DATA_DIR");
}

std::string versionText(std::string_view tool) {
    const nlohmann::json build = buildInfo();
#if VRI_HAVE_VULKAN
    constexpr const char* kVulkan = "with";
#else
    constexpr const char* kVulkan = "without";
#endif
    return std::string(tool) + " (vri) " + build["vri_version"].get<std::string>() + "\ngit commit " +
           build["git_commit"].get<std::string>() + ", " + build["build_type"].get<std::string>() +
           " build, " + build["compiler"].get<std::string>() + ", " + kVulkan + " the Vulkan backend";
}

std::optional<int> parseArguments(CLI::App& app, std::string_view tool, int argc, char** argv) {
    app.set_version_flag("--version", [tool] { return versionText(tool); },
                         "print the version, git commit, build type and compiler, and exit");
    checkNumberText(app);
    takeWordsAsTyped(app);
    try {
        refuseEmptyValues(app, argc, argv);
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --help-all, --version
        return app.exit(e);
    } catch (const CLI::ConversionError& e) {
        std::cerr << tool << ": error: " << printable(conversionMessage(app, e.what())) << " (see --help)\n";
        return kExitUsage;
    } catch (const CLI::ParseError& e) {
        std::cerr << tool << ": error: " << printable(e.what()) << " (see --help)\n";
        return kExitUsage;
    }
    return std::nullopt;
}

void requireUtf8Arguments(int argc, char** argv, std::string_view why) {
    for (int i = 1; i < argc; ++i)
        if (const auto at = firstInvalidUtf8(argv[i]))
            throw UsageError("argument " + std::to_string(i) + " '" + escapeInvalidUtf8(argv[i]) +
                             "' is not valid UTF-8 (byte " + std::to_string(*at) + "): " + std::string(why));
}

std::string describeUnexpected(const std::exception& e) {
    if (dynamic_cast<const std::bad_alloc*>(&e))
        return "out of memory: the input asks for more memory than is available (sizes from input are checked "
               "against VRI_MAX_BYTES, 16 GiB by default; lower it to be refused before allocating)";
    if (const auto* fsError = dynamic_cast<const std::filesystem::filesystem_error*>(&e))
        return (fsError->path1().empty() ? std::string("file system") : fsError->path1().string()) + ": " +
               fsError->code().message();
    if (const auto* jsonError = dynamic_cast<const nlohmann::json::exception*>(&e)) {
        constexpr int kInvalidUtf8 = 316;  // nlohmann's type_error.316, raised while writing
        if (jsonError->id == kInvalidUtf8)
            return "a file name or text to be written as JSON is not valid UTF-8 (" + jsonExceptionText(*jsonError) +
                   ")";
        return "JSON: " + jsonExceptionText(*jsonError);
    }
    return e.what();
}

void requireExrOutput(const OutputArgument& output) {
    std::string extension = fs::path(output.path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".exr")
        throw UsageError(output.option + ": '" + output.path +
                         "' is not an .exr file (the image is float RGBA OpenEXR; --png writes an 8-bit preview)");
}

void requireDistinctOutputs(const std::vector<OutputArgument>& outputs) {
    std::vector<fs::path> identities(outputs.size());  // empty: not asked for, or standard output
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        if (outputs[i].path == "-") {  // two outputs on standard output would run into each other
            for (std::size_t j = 0; j < i; ++j)
                if (outputs[j].path == "-")
                    throw UsageError(outputs[i].option + ": '-' (standard output) is also " + outputs[j].option +
                                     "'s output");
            continue;
        }
        if (outputs[i].path.empty()) continue;
        try {
            identities[i] = fileIdentity(outputs[i].path);  // refuses what no write could replace
        } catch (const Error& e) {
            throw Error(outputs[i].option + ": " + e.what());
        }
        for (std::size_t j = 0; j < i; ++j)
            if (!identities[j].empty() &&  // the same path, or hard links: two names, one inode
                (identities[i] == identities[j] || sameExistingFile(outputs[i].path, outputs[j].path)))
                throw UsageError(outputs[i].option + ": '" + outputs[i].path + "' is also " + outputs[j].option +
                                 "'s output");
    }
}

std::vector<InputArgument> volumeInputArguments(const std::string& option, const std::string& path) {
    if (path.empty()) return {};
    std::vector<InputArgument> inputs;
    for (const fs::path& file : filesReadBy(path))
        inputs.push_back({inputs.empty() ? option : option + "'s data file", file.string()});
    return inputs;
}

void requireOutputsApartFromInputs(const std::vector<OutputArgument>& outputs,
                                   const std::vector<InputArgument>& inputs) {
    for (const OutputArgument& output : outputs) {
        if (output.path.empty() || output.path == "-") continue;
        for (const InputArgument& input : inputs)
            if (!input.path.empty() && input.path != "-" && sameExistingFile(output.path, input.path))
                throw UsageError(output.option + " '" + output.path + "' is the same file as " + input.option + " '" +
                                 input.path + "'");
    }
}

}  // namespace vri
