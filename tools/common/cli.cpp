#include "common/cli.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <new>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/io/provenance.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/atomic_file.h"
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

// The length of a decimal integer's sign ("-12": 1, "12": 0), or npos for a value that is not one.
std::size_t decimalSign(const std::string& value) {
    const std::size_t sign = !value.empty() && (value[0] == '+' || value[0] == '-') ? 1 : 0;
    const bool digits = value.size() > sign &&
                        std::all_of(value.begin() + sign, value.end(), [](unsigned char c) { return std::isdigit(c); });
    return digits ? sign : std::string::npos;
}

// A decimal integer with leading zeros ("010", "-007") without them, anything else as it is. CLI11 reads an
// integer option with strtoll in base 0, where a leading 0 means octal ("010" is 8, "08" an error); every other
// number a tool reads is decimal or hexadecimal after 0x (parse.h), and so are these once the zeros are gone.
std::string withoutLeadingZeros(const std::string& value) {
    const std::size_t sign = decimalSign(value);
    if (sign == std::string::npos || value[sign] != '0') return value;
    const std::size_t first = std::min(value.find_first_not_of('0', sign), value.size() - 1);
    return value.substr(0, sign) + value.substr(first);
}

bool isIntegerType(const std::string& type) { return type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0; }

// Gives every integer option of the app and its option groups the transform above, ahead of its validators.
void readIntegersAsDecimal(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        if (isIntegerType(option->get_type_name())) option->transform(withoutLeadingZeros);
    }
    for (CLI::App* group : app.get_subcommands({}))
        if (group->get_name().empty()) readIntegersAsDecimal(*group);
}

// CLI11's "Could not convert: --fov = abc" as "--fov: expected a number, got 'abc'": the option and what it
// takes, from the option's type; a message of another form as it is.
std::string conversionMessage(const CLI::App& app, const std::string& what) {
    constexpr std::string_view prefix = "Could not convert: ";
    const std::size_t equals = what.find(" = ");
    if (what.rfind(prefix, 0) != 0 || equals == std::string::npos) return what;
    const std::string name = what.substr(prefix.size(), equals - prefix.size());
    const CLI::Option* option = app.get_option_no_throw(name);
    if (!option) return what;
    const std::string type = option->get_type_name();
    const std::string value = what.substr(equals + 3);
    if (isIntegerType(type)) {
        // Decimal digits that did not convert lie outside the option's integer type.
        if (decimalSign(value) != std::string::npos) return name + ": " + value + " is outside the range of this integer option";
        return name + ": expected an integer (decimal, or hexadecimal after 0x), got '" + value + "'";
    }
    if (type.rfind("FLOAT", 0) != 0) return what;
    return name + ": expected a number, got '" + value + "'";
}

}  // namespace

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
    readIntegersAsDecimal(app);
    try {
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
