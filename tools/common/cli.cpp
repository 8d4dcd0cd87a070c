#include "common/cli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <malloc.h>
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

// "--name=" with nothing after '=': CLI11 would take the next word for the value, whatever it is ("--row= A"
// read as "--row A", "--threshold= --json" as a threshold "--json"). Refused for an option that takes values,
// up to the "--" that ends the options.
void refuseEmptyAfterEquals(const CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc && std::string_view(argv[i]) != "--"; ++i) {
        const std::string_view word = argv[i];
        if (!word.starts_with("--") || !word.ends_with('=')) continue;
        const CLI::Option* option = app.get_option_no_throw(std::string(word.substr(0, word.size() - 1)));
        if (option && option->get_items_expected_max() > 0)
            throw CLI::ValidationError(option->get_name(), "nothing after '=' (give the value after '=' or as the "
                                                           "next word)");
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

namespace {

// A list option's items in one word, split at single commas; an empty item is a usage error.
std::vector<std::string> listItems(const std::string& word, const std::string& option) {
    try {
        return parseWordList(word, option);
    } catch (const Error& e) {
        throw CLI::ValidationError(e.what());
    }
}

// The name an option's messages give: the long one of "-o,--output".
std::string optionLabel(const std::string& names) { return names.substr(names.rfind(',') + 1); }

std::string commaJoined(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
    return text;
}

}  // namespace

CLI::Option* addListOption(CLI::App& app, const std::string& name, std::vector<double>& items,
                           const std::string& description, std::optional<CLI::Validator> check, std::size_t count) {
    std::vector<std::string> defaults;
    for (double item : items) defaults.push_back(exactNumber(item));
    const std::string label = optionLabel(name);
    CLI::Option* option = app.add_option(name, [&items, label, check, count](const CLI::results_t& words) {
        std::vector<double> read;
        for (const std::string& word : words) {
            std::vector<std::string> texts = listItems(word, label);
            if (count && (texts.size() != count || words.size() > 1))
                throw CLI::ValidationError(label, "expected " + std::to_string(count) +
                                                      " numbers separated by ',', once, got '" + word + "'" +
                                                      (words.size() > 1 ? " among " + std::to_string(words.size()) + " uses" : ""));
            for (std::string& text : texts) {
                const std::optional<double> number = numberFromText(text);
                if (!number) throw CLI::ValidationError(label, "expected a number, got '" + text + "'");
                if (check)
                    if (const std::string why = (*check)(text); !why.empty()) throw CLI::ValidationError(label, why);
                read.push_back(*number);
            }
        }
        items = std::move(read);
        return true;
    }, description);
    return option->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->type_name(count ? "NUMBER,NUMBER" : "NUMBER,...")
        ->default_str(commaJoined(defaults));
}

CLI::Option* addListOption(CLI::App& app, const std::string& name, std::vector<std::string>& items,
                           const std::string& description) {
    const std::string defaults = commaJoined(items);
    const std::string label = optionLabel(name);
    CLI::Option* option = app.add_option(name, [&items, label](const CLI::results_t& words) {
        std::vector<std::string> read;
        for (const std::string& word : words)
            for (std::string& item : listItems(word, label)) read.push_back(std::move(item));
        items = std::move(read);
        return true;
    }, description);
    return option->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->type_name("TEXT,...")->default_str(defaults);
}

CLI::Option* addWordsOption(CLI::App& app, const std::string& name, std::vector<std::vector<std::string>>& uses,
                            const std::string& usage, int least, int most, const std::string& description) {
    const std::string label = optionLabel(name);
    // Triggered at each use, so that each use's words arrive on their own, exactly as typed.
    CLI::Option* option = app.add_option(name, [&uses, label, usage, least](const CLI::results_t& words) {
        for (const std::string& word : words)
            if (word.empty()) throw CLI::ValidationError(label, "an empty word cannot be one of its values");
        if (static_cast<int>(words.size()) < least)
            throw CLI::ValidationError(label, "expected " + usage + ", got " + std::to_string(words.size()) +
                                                  (words.size() == 1 ? " word" : " words"));
        uses.push_back(words);
        return true;
    }, description);
    return option->trigger_on_parse()->allow_extra_args(false)->expected(1, most)->type_name(usage);
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
    try {
        refuseEmptyAfterEquals(app, argc, argv);
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

void retainFreedMemory() {
    constexpr int kMmapThreshold = 32 << 20;  // glibc's largest: below it a block comes from the heap
    mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());  // the heap's top is never given back
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
