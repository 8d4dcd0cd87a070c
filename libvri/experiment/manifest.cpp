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

// The first line `git -C dir ARGS...` prints, or "" when it cannot run (no git, not a work tree).
std::string firstLineOfGit(const fs::path& dir, std::vector<std::string> args) {
    const auto git = findProgram("git");
    if (!git) return "";
    std::vector<std::string> words{"git", "-C", dir.string()};
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

// "commit 0123456789ab" (12 digits, as git shows short ids), with "(tracked files modified)" when the
// tree was dirty: what the gallery says an experiment's results were made from.
std::string commitNote(const nlohmann::json& sourceTree) {
    const std::string commit = sourceTree.at("commit").get<std::string>();
    if (commit == "unknown") return "commit unknown";
    std::string note = "commit `" + commit.substr(0, 12) + "`";
    if (sourceTree.value("modified_files", false)) note += " (tracked files modified)";
    return note;
}

// The caption of an experiment's heat maps: what they show and each one's scale, read from the
// comparison's vri-diff JSON beside it (a diff image is named as its JSON: <comparison id>.png). Maps
// that share a scale (vri-diff --scale-over, `diff_scale: shared`) are listed together, the top once.
void heatMapScales(std::ostream& md, const nlohmann::json& diffImages, const fs::path& dir) {
    std::vector<std::pair<std::string, std::string>> scales;  // ids, the top they share or have alone
    for (const nlohmann::json& item : diffImages) {
        const std::string id = item.at("id").get<std::string>();
        const fs::path json = dir / (id + ".json");
        if (!fs::is_regular_file(json)) continue;
        const nlohmann::json diff = readJsonFile(json);
        if (!diff.contains("heat_map")) continue;  // results of a vri-diff that drew RGB on black
        char top[32];
        std::snprintf(top, sizeof top, "%.3g", readingJsonOf(json, [&] { return diff.at("heat_map").at("top").get<double>(); }));
        const bool shared = diff.at("heat_map").contains("scale_over");
        if (shared && !scales.empty() && scales.back().second == top + std::string(" (one scale)"))
            scales.back().first += ", " + id;
        else
            scales.emplace_back(id, top + std::string(shared ? " (one scale)" : ""));
    }
    if (scales.empty()) return;
    md << "*Difference images: heat maps of the largest |run - reference| over the channels (alpha included), "
          "viridis from 0 (dark blue, the colour bar's left end) to the top of the scale (yellow, its right end; "
          "larger errors saturate), the bar numbered at quarters of it. Top of the scale: ";
    for (std::size_t i = 0; i < scales.size(); ++i) md << (i ? "; " : "") << scales[i].first << " " << scales[i].second;
    md << ".*\n\n";
}

// A table's Markdown without the notes under its last row when an earlier table of the experiment had
// the same: a kind of table is explained once, not under each of its tables.
std::string withNewNotes(const std::string& table, std::set<std::string>& notesSeen) {
    const std::size_t lastRow = table.rfind("\n|");
    const std::size_t rowEnd = lastRow == std::string::npos ? std::string::npos : table.find('\n', lastRow + 1);
    if (rowEnd == std::string::npos) return table;
    const std::string notes = table.substr(rowEnd + 1);
    if (notes.find_first_not_of(" \n") == std::string::npos || notesSeen.insert(notes).second) return table;
    return table.substr(0, rowEnd + 1);
}

// An id without the scene's name in front (bonsai-riemann-h0.5 -> riemann-h0.5): the same run's
// column in every scene's row.
std::string withoutScene(const std::string& id, const std::string& scene) {
    return !scene.empty() && id.starts_with(scene + "-") ? id.substr(scene.size() + 1) : id;
}

// Where each gallery image goes in its experiment's scene-by-run matrix: a render's row is its scene
// and its column its run; a difference image's row is its run's scene and its column "RUN vs REFERENCE",
// or its comparison's id when another comparison of the same pair took that column already (two
// comparisons of one run, say on different scales). A command's image has no scene.
std::vector<GridImage> gridImages(const nlohmann::json& list, const nlohmann::json& steps, const std::string& dir) {
    std::map<std::string, const nlohmann::json*> parameters;
    for (const nlohmann::json& step : steps) parameters.emplace(step.at("id").get<std::string>(), &step.at("parameters"));
    const auto scene = [&](const std::string& id) {
        const auto found = parameters.find(id);
        return found == parameters.end() ? std::string() : found->second->value("scene", std::string());
    };
    std::vector<GridImage> images;
    std::set<std::pair<std::string, std::string>> cells;  // (row, column) taken
    for (const nlohmann::json& item : list) {
        const std::string id = item.at("id").get<std::string>();
        GridImage image{id, dir + "/" + item.at("file").get<std::string>(), scene(id), id};
        if (const auto found = parameters.find(id); found != parameters.end() && found->second->contains("run")) {
            const std::string run = found->second->at("run").get<std::string>();
            const std::string reference = found->second->value("reference", std::string());
            image.row = scene(run);
            image.column = withoutScene(run, image.row) + " vs " + withoutScene(reference, scene(reference));
            if (cells.contains({image.row, image.column})) image.column = withoutScene(id, image.row);
        } else {
            image.column = withoutScene(id, image.row);
        }
        cells.emplace(image.row, image.column);
        images.push_back(std::move(image));
    }
    return images;
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
    writeTextFile(plan.resultsDir / "manifest.json", manifest.dump(2) + "\n");
}

std::string galleryMarkdown(const fs::path& resultsRoot) {
    std::vector<fs::path> manifests;
    for (const fs::directory_entry& entry : fs::directory_iterator(resultsRoot))
        if (fs::is_regular_file(entry.path() / "manifest.json")) manifests.push_back(entry.path() / "manifest.json");
    std::sort(manifests.begin(), manifests.end());

    std::ostringstream md;
    md << "# Results\n\n"
          "Generated by `vri-run --gallery` from each experiment's `manifest.json`; regenerate everything with\n"
          "`make experiments`. Each experiment's folder holds its images, tables, figures and the manifest with the\n"
          "exact commands, input digests, build, machine and wall times.\n";
    std::map<std::string, std::string> notedIn;  // a dataset that is not exact: the experiment that notes it
    for (const fs::path& path : manifests) readingJsonOf(path, [&] {
        const nlohmann::json m = readJsonFile(path);
        const nlohmann::json& e = m.at("experiment");
        const std::string dir = path.parent_path().filename().string();
        md << "\n## " << e.at("title").get<std::string>() << "\n\n";
        const nlohmann::json& paper = e.at("paper");
        if (paper.at("paper") != "none")
            md << "**Paper " << paper.at("paper").get<std::string>() << ", " << paper.at("item").get<std::string>()
               << ":** " << paper.at("says").get<std::string>() << "\n\n";
        for (const nlohmann::json& d : m.at("datasets")) {
            const std::string dataset = d.at("dataset").get<std::string>();
            if (d.at("status") == "exact" || (notedIn.contains(dataset) && notedIn.at(dataset) == dir)) continue;
            md << "*Dataset " << dataset << " is " << d.at("status").get<std::string>();
            if (const auto first = notedIn.emplace(dataset, dir); first.second)
                md << ":* " << d.at("note").get<std::string>() << "\n\n";
            else
                md << "* (see " << first.first->second << ").\n\n";
        }
        const nlohmann::json& outputs = m.at("outputs");
        md << imageGrid(gridImages(outputs.at("images"), m.at("steps"), dir), "scene");
        md << imageGrid(gridImages(outputs.at("diff_images"), m.at("steps"), dir), "scene");
        heatMapScales(md, outputs.at("diff_images"), path.parent_path());
        std::set<std::string> notesSeen;
        for (const nlohmann::json& table : outputs.at("tables"))
            if (const auto text = tryReadFileText(path.parent_path() / table.at("file").get<std::string>()); text && !text->empty())
                md << withNewNotes(*text, notesSeen) << "\n";
        // A figure is as wide as the page: one a line.
        for (const nlohmann::json& figure : outputs.at("figures"))
            md << "![" << figure.at("id").get<std::string>() << "](" << dir << "/" << figure.at("file").get<std::string>()
               << ")\n\n";
        if (!e.at("agreement").get<std::string>().empty())
            md << "**Ours against the paper:** "
               << fillCaptionNumbers(e.at("agreement").get<std::string>(), path.parent_path()) << "\n\n";
        md << "Experiment file `" << e.at("source").get<std::string>() << "`, " << commitNote(m.at("source_tree"))
           << ", manifest [" << dir << "/manifest.json](" << dir << "/manifest.json); from nothing its "
           << m.at("steps").size() << (m.at("steps").size() == 1 ? " step takes " : " steps take ")
           << secondsText(manifestSeconds(m)) << ".\n";
    });
    return md.str();
}

}  // namespace vri
