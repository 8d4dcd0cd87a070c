// manifest.json of an experiment, and the results gallery read back from the manifests.
#include "libvri/experiment/manifest.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "libvri/experiment/caption_numbers.h"
#include "libvri/experiment/gallery_grid.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/io/provenance.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"
#include "libvri/util/json_file.h"
#include "libvri/util/process.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// The first line `git -C dir ARGS...` prints, or "" when it cannot run (no git, not a work tree). Without
// optional locks: `git status` would otherwise refresh the user's index and write it, where vri-run only reads.
std::string firstLineOfGit(const fs::path& dir, std::vector<std::string> args) {
    const auto git = findProgram("git");
    if (!git) return "";
    std::vector<std::string> words{"git", "--no-optional-locks", "-C", dir.string()};
    words.insert(words.end(), std::make_move_iterator(args.begin()), std::make_move_iterator(args.end()));
    try {
        auto [status, output] =
            captureProcess(*git, words, {.in = "/dev/null", .out = {}, .err = "/dev/null", .errToOut = false});
        if (!status.ok()) return "";
        output = output.substr(0, output.find('\n'));
        if (!output.empty() && output.back() == '\r') output.pop_back();
        return output;
    } catch (const Error&) {
        return "";  // git could not be started: the source tree is unknown, not a failed experiment
    }
}

nlohmann::json sourceTree(const fs::path& experimentFile) {
    const std::optional<WorkTree> tree = workTreeOf(experimentFile);
    if (!tree) return {{"commit", "unknown"}};
    return {{"commit", tree->commit}, {"modified_files", tree->modified}};
}

std::string stateName(StepOutcome::State state) {
    switch (state) {
    case StepOutcome::State::Ran: return "ran";
    case StepOutcome::State::Cached: return "cached";
    case StepOutcome::State::Unavailable: return "tool not built";
    }
    return "unknown";
}

// The list of the manifest's "outputs" (what the gallery shows) that a step's output file belongs
// to, or "" for none: previews and command images, diff images, Markdown tables, figures.
std::string galleryList(const Step& step, const fs::path& file) {
    const std::string ext = file.extension().string();
    const bool madeImage = step.kind == "render" || step.kind == "command";
    const bool madeTable = step.kind == "table" || step.kind == "command";
    if (ext == ".png" && madeImage) return "images";
    if (ext == ".png" && step.kind == "diff") return "diff_images";
    if (ext == ".md" && madeTable) return "tables";
    if (ext == ".png" && step.kind == "figure") return "figures";
    return "";
}

}  // namespace

std::optional<WorkTree> workTreeOf(const fs::path& file) {
    const fs::path dir = fs::absolute(file).parent_path();
    const std::string commit = firstLineOfGit(dir, {"rev-parse", "HEAD"});
    const std::string top = firstLineOfGit(dir, {"rev-parse", "--show-toplevel"});
    if (commit.empty() || top.empty()) return std::nullopt;
    // results/ itself is left out: it is what vri-run writes, and one experiment's new results must not
    // make the next one's tree dirty.
    const bool modified =
        !firstLineOfGit(dir, {"status", "--porcelain", "--untracked-files=no", "--", ":/", ":(top,exclude)results"})
             .empty();
    return WorkTree{top, commit, modified};
}

void writeManifest(const Experiment& experiment, const Plan& plan, const std::vector<StepOutcome>& outcomes,
                   const fs::path& toolDir, FileHasher& hasher) {
    nlohmann::json steps = nlohmann::json::array();
    nlohmann::json tools = nlohmann::json::object();
    nlohmann::json outputs = {{"images", nlohmann::json::array()}, {"diff_images", nlohmann::json::array()},
                              {"tables", nlohmann::json::array()}, {"figures", nlohmann::json::array()}};
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        const Step& step = plan.steps[i];
        const StepOutcome& outcome = outcomes.at(i);
        nlohmann::json parameters = nlohmann::json::object();
        for (const auto& [key, value] : step.parameters) parameters[key] = value;
        steps.push_back({{"id", step.id},
                         {"kind", step.kind},
                         {"state", stateName(outcome.state)},
                         {"command", outcome.record.command},
                         {"parameters", parameters},
                         {"inputs", toJson(outcome.record.inputs)},
                         {"outputs", toJson(outcome.record.outputs)},
                         {"wall_seconds", outcome.record.wallSeconds},
                         {"ran_utc", outcome.record.ranUtc},
                         {"execution", toJson(outcome.record.execution)}});
        if (outcome.state == StepOutcome::State::Unavailable) continue;
        tools[step.tool] = hasher.digest(toolDir / step.tool);
        for (const fs::path& out : step.outputs)
            if (const std::string list = galleryList(step, out); !list.empty())
                outputs[list].push_back({{"id", step.id}, {"file", out.lexically_relative(plan.resultsDir).string()}});
    }
    nlohmann::json datasets = nlohmann::json::array();
    for (const SceneSpec& scene : experiment.scenes)
        if (!scene.dataset.empty())
            datasets.push_back({{"scene", scene.name}, {"dataset", scene.dataset}, {"status", scene.datasetStatus},
                                {"note", scene.datasetNote}});
    nlohmann::json manifest = {
        {"experiment",
         {{"name", experiment.name},
          {"title", experiment.title},
          {"paper", {{"paper", experiment.paper.paper}, {"item", experiment.paper.item}, {"says", experiment.paper.says}}},
          {"agreement", experiment.agreement},
          {"source", plan.commandPath(fs::absolute(experiment.source).lexically_normal())},
          {"source_sha512", hasher.digest(experiment.source)},
          {"quick", experiment.quick}}},
        {"source_tree", sourceTree(experiment.source)},
        {"build", buildInfo()},
        {"machine", machineInfo()},
        {"tools", tools},
        {"datasets", datasets},
        {"outputs", outputs},
        {"steps", steps}};
    // Only where the file left something out, so that a complete file's manifest is as it was.
    if (!experiment.defaults.empty()) manifest["experiment"]["defaults"] = experiment.defaults;
    if (!plan.part.empty()) manifest["part"] = plan.part;
    writeTextFile(plan.resultsDir / "manifest.json", manifest.dump(2) + "\n");
}

}  // namespace vri
