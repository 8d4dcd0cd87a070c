#include "libvri/experiment/slurm_profile.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "libvri/experiment/slurm_commands.h"
#include "libvri/io/yaml_util.h"
#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// "512M", "4G" or a number of MiB.
long long mebibytes(const YAML::Node& node, const std::string& source) {
    std::string text = yaml::toString(node, source, "mem");
    long long scale = 1;
    if (!text.empty() && std::string_view("GgMm").find(text.back()) != std::string_view::npos) {
        scale = text.back() == 'G' || text.back() == 'g' ? 1024 : 1;
        text.pop_back();
    }
    char* end = nullptr;
    const bool digits = !text.empty() && std::isdigit(static_cast<unsigned char>(text.front()));  // no blank, no sign
    const long long n = digits ? std::strtoll(text.c_str(), &end, 10) : 0;
    constexpr long long kMostMiB = 1LL << 40;  // a mebibyte count sbatch takes, well within 64 bits once scaled
    if (!digits || *end != '\0' || n < 1 || n > kMostMiB / scale)
        throw Error(yaml::where(source, node) + ": mem: expected mebibytes as N, NM or NG, got '" + node.Scalar() +
                    "'");
    return n * scale;
}

StepKindResources kindResources(const YAML::Node& node, const std::string& source) {
    yaml::requireMap(node, source, "a kind");
    yaml::requireKeys(node, source, {"cpus", "mem", "time"});
    StepKindResources r;
    if (node["cpus"]) r.cpus = static_cast<int>(yaml::toWholeNumber(node["cpus"], source, "cpus", 1, 1024));
    if (node["mem"]) r.memoryMiB = mebibytes(node["mem"], source);
    if (node["time"]) r.minutes = yaml::toWholeNumber(node["time"], source, "time", 1, 525600);  // a year of minutes
    return r;
}

}  // namespace

std::string slurmStepKind(const Step& step) {
    if (step.tool == "vri-merge-tiles") return "merge";
    if (step.tool == "vri-outside" || step.tool == "vri-verify") return "outside";
    for (const auto& [key, value] : step.parameters) {
        if (key == "region") return "tile";
        if (key == "brick") return "brick";
    }
    return step.kind;
}

SlurmProfile readSlurmProfile(const fs::path& path) {
    const std::string source = path.string();
    const YAML::Node root = yaml::load(path);
    yaml::requireMap(root, source, "a Slurm profile");
    yaml::requireKeys(root, source, {"account", "partition", "qos", "constraint", "cpus", "args", "kinds"});
    SlurmProfile profile;
    for (const char* key : {"account", "partition", "qos", "constraint"})
        if (const YAML::Node value = root[key]) {
            const std::string word = "--" + std::string(key) + "=" + yaml::toString(value, source, key);
            checkSiteSbatchOption(word, yaml::where(source, value));
            profile.sbatchArguments.push_back(word);
        }
    if (root["cpus"]) profile.cpus = static_cast<int>(yaml::toWholeNumber(root["cpus"], source, "cpus", 1, 1024));
    if (const YAML::Node args = root["args"]) {
        if (!args.IsSequence()) throw Error(yaml::where(source, args) + ": args: expected a list of sbatch options");
        for (const YAML::Node& arg : args) {
            const std::string word = yaml::toString(arg, source, "args");
            checkSiteSbatchOption(word, yaml::where(source, arg));
            profile.sbatchArguments.push_back(word);
        }
    }
    if (const YAML::Node kinds = root["kinds"]) {
        yaml::requireMap(kinds, source, "kinds");
        for (const auto& kv : kinds) {
            const std::string kind = yaml::toString(kv.first, source, "a kind");
            if (std::ranges::find(kSlurmStepKinds, kind) == std::end(kSlurmStepKinds))
                throw Error(yaml::where(source, kv.first) + ": unknown kind of step '" + kind +
                            "' (expected render, tile, brick, merge, diff, table, figure or command)");
            profile.kinds[kind] = kindResources(kv.second, source);
        }
    }
    return profile;
}

std::optional<fs::path> slurmProfilePath() {
    if (const char* named = std::getenv("VRI_SLURM_PROFILE"); named && *named) {
        if (!fs::is_regular_file(named)) throw Error(std::string("VRI_SLURM_PROFILE: ") + named + ": no such file");
        return fs::path(named);
    }
    if (const char* home = std::getenv("HOME"); home && *home) {
        const fs::path standard = fs::path(home) / ".config" / "vri" / "slurm.yaml";
        if (fs::is_regular_file(standard)) return standard;
    }
    return std::nullopt;
}

}  // namespace vri
