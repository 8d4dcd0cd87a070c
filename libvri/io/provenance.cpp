#include "libvri/io/provenance.h"

#include <sched.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include <OpenEXR/OpenEXRConfig.h>
#include <OpenImageIO/oiioversion.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/version.h>
#include <openvdb/version.h>  // macros only: cheap, unlike openvdb/openvdb.h
#include <png.h>

#include "libvri/core/engine_environment.h"
#include "libvri/core/simd_target.h"
#include "vri_git_commit.h"  // generated at every build: VRI_GIT_COMMIT

namespace vri {

namespace {

const std::string kUnknown = "unknown";

std::string trim(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\"'");
    if (first == std::string_view::npos) return {};
    const auto last = text.find_last_not_of(" \t\"'\r");
    return std::string(text.substr(first, last - first + 1));
}

// The value after the first line of `path` that starts with `key` and then `separator`
// ("model name\t: Intel...", "MemTotal:  16 kB", PRETTY_NAME="Debian..."), quotes and blanks trimmed.
std::string findField(const char* path, std::string_view key, char separator) {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with(key)) continue;
        const auto at = line.find(separator, key.size());
        if (at != std::string::npos && trim(line.substr(key.size(), at - key.size())).empty())
            return trim(std::string_view(line).substr(at + 1));
    }
    return {};
}

std::string orUnknown(std::string value) { return value.empty() ? kUnknown : value; }

std::uint64_t memoryBytes() {
    const std::string total = findField("/proc/meminfo", "MemTotal", ':');  // "16318480 kB"
    try {
        return total.ends_with("kB") ? std::stoull(total) * 1024 : 0;
    } catch (const std::exception&) {
        return 0;
    }
}

int usableCores() {
    cpu_set_t set;
    return sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
}

std::string kernelRelease() {
    utsname info;
    return uname(&info) == 0 ? orUnknown(info.release) : kUnknown;
}

// The CPU's vector extensions a SIMD target needs (x86 "flags", Arm "Features"), in /proc/cpuinfo's order: a
// benchmark's reader needs them beside the model name, which a virtual machine often hides ("AMD EPYC").
std::vector<std::string> cpuSimdFlags() {
    static const std::set<std::string, std::less<>> wanted = {
        "sse4_1", "sse4_2", "avx", "avx2", "fma", "f16c", "bmi2", "avx512f", "avx512cd", "avx512dq", "avx512bw",
        "avx512vl", "avx512_vnni", "avx512vbmi", "avx512_vbmi2", "avx512_bf16", "avx512_fp16", "asimd", "sve", "sve2"};
    std::string line = findField("/proc/cpuinfo", "flags", ':');
    if (line.empty()) line = findField("/proc/cpuinfo", "Features", ':');
    std::vector<std::string> flags;
    std::istringstream words(line);
    for (std::string w; words >> w;)
        if (wanted.contains(w)) flags.push_back(w);
    return flags;
}

}  // namespace

std::string hostName() {
    char name[256] = {};
    return gethostname(name, sizeof name - 1) == 0 ? orUnknown(name) : kUnknown;
}

nlohmann::json machineInfo() {
    return {{"cpu_model", orUnknown(findField("/proc/cpuinfo", "model name", ':'))},
            {"cpu_simd_flags", cpuSimdFlags()},
            {"simd_targets", availableSimdTargets()},  // the ones --simd may name, best first
            {"logical_cores", std::thread::hardware_concurrency()},
            {"usable_cores", usableCores()},
            {"memory_bytes", memoryBytes()},
            {"os", orUnknown(findField("/etc/os-release", "PRETTY_NAME", '='))},
            {"kernel", kernelRelease()},
            {"hostname", hostName()}};
}

nlohmann::json buildInfo() {
    return {{"vri_version", VRI_VERSION},
            {"git_commit", VRI_GIT_COMMIT},
            {"build_type", VRI_BUILD_TYPE},
            {"compiler", VRI_COMPILER},
            {"openexr", OPENEXR_VERSION_STRING},
            {"libpng", PNG_LIBPNG_VER_STRING},
            {"openimageio", OIIO_VERSION_STRING},  // the module for formats other than EXR and PNG
            {"openvdb", OPENVDB_LIBRARY_VERSION_STRING},
            {"tbb", TBB_VERSION_STRING}};
}

std::string shellQuote(std::string_view word) {
    const auto safe = [](char ch) {
        return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
               std::string_view("_@%+=:,./-").find(ch) != std::string_view::npos;
    };
    // As a command's first word, NAME=value is an assignment and %N a job: quoted, they are words anywhere.
    const auto assignment = word.substr(0, word.find('='));
    const bool readsAsAssignment = assignment.size() < word.size() && !assignment.empty() &&
                                   !std::isdigit(static_cast<unsigned char>(assignment.front())) &&
                                   std::all_of(assignment.begin(), assignment.end(), [](char ch) {
                                       return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                                   });
    if (!word.empty() && word.front() != '%' && !readsAsAssignment && std::all_of(word.begin(), word.end(), safe))
        return std::string(word);
    std::string quoted = "'";
    for (char ch : word) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return quoted + "'";
}

nlohmann::json commandLine(int argc, char** argv) {
    nlohmann::json args = nlohmann::json::array(), environment = nlohmann::json::object();
    std::string shell;
    for (const auto& [name, value] : engineEnvironment()) {  // assignments before the command: its environment
        environment[name] = value;
        shell += name + "=" + shellQuote(value) + " ";
    }
    for (int i = 0; i < argc; ++i) {
        args.push_back(argv[i]);
        if (i > 0) shell += ' ';
        shell += shellQuote(argv[i]);
    }
    nlohmann::json command = {{"argv", std::move(args)}, {"shell", shell}};
    if (!environment.empty()) command["environment"] = std::move(environment);
    return command;
}

std::string utcTimestamp() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace vri
