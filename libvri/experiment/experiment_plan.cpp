// From an experiment to the command lines of its steps, and the order they can run in.
#include "libvri/experiment/experiment_plan.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>

#include "libvri/core/brick_grid.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/core/render_option_table.h"
#include "libvri/core/scene_flags.h"
#include "libvri/io/plot_data_files.h"
#include "libvri/io/provenance.h"
#include "libvri/render/tool_flags.h"
#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// The bytes of the voxels `box` of a volume of `shape`: what a step holding them stores (Step::volumeBytes).
std::uint64_t heldBytes(const VolumeShape& shape, const VoxelBox& box) {
    return box.voxelCount() * voxelSize(shape.type);
}

// `path` as a command names it when run from `workDir`: relative when the two share more than the root.
std::string displayPath(const fs::path& path, const fs::path& workDir) {
    const fs::path relative = path.lexically_relative(workDir);
    const auto workDepth = std::distance(workDir.begin(), workDir.end()) - 1;  // components below the root
    const auto up = std::count(relative.begin(), relative.end(), fs::path(".."));
    if (relative.empty() || up >= workDepth) return path.string();
    return relative.string();
}

// Values as one option word: "0.01,0.005,0.001".
std::string commaList(const std::vector<std::string>& values) {
    std::string list;
    for (const std::string& v : values) list += (list.empty() ? "" : ",") + v;
    return list;
}

// Absolute, normal, without a trailing separator (which would count as one more component).
fs::path normalDirectory(const fs::path& dir) {
    fs::path normal = fs::absolute(dir).lexically_normal();
    if (!normal.has_filename() && normal != normal.root_path()) normal = normal.parent_path();
    return normal;
}

class Planner {
public:
    Planner(const Experiment& experiment, Plan& plan) : experiment_(experiment), plan_(plan) {}

    void addRender(const RunSpec& run);
    // A scene's options, its volume and transfer function as inputs (a render, or a command with a scene).
    void sceneOptions(Step& step, const SceneSpec& scene) const;
    void addTiles(const RunSpec& run, const SceneSpec& scene, const Step& render);
    void addBricks(const RunSpec& run, const SceneSpec& scene, const Step& render);
    void addLayerTiles(const RunSpec& run, const SceneSpec& scene, const Step& brick);
    // One part of a split run (a tile or a brick): what its step adds to the render's.
    struct RunPart {
        std::string suffix;                             // of the run's id: ".tile-1", ".brick-0-1-0"
        std::vector<std::string> arguments;             // --region X,Y,W,H; --bricks G --brick I,J,K
        std::pair<std::string, std::string> parameter;  // what the part stands for, for the manifest
        std::uint64_t pixels;                           // it renders
        int volumeParts;                                // Step::volumeParts
        std::uint64_t volumeBytes;                      // Step::volumeBytes
    };
    // A step per part, then the vri-merge-tiles step (`mergeFlag` per part) writing the unsplit run's files.
    void addSplit(const RunSpec& run, const SceneSpec& scene, const Step& render, const char* mergeFlag,
                  const std::pair<std::string, std::string>& mergeParameter, const std::vector<RunPart>& parts);
    void addDiff(const ComparisonSpec& comparison);
    void addCommand(const CommandSpec& command);
    void addTable(const TableSpec& table);
    void addFigure(const FigureSpec& figure);

private:
    fs::path result(const std::string& name) const { return plan_.resultsDir / name; }
    std::string show(const fs::path& path) const { return displayPath(path, plan_.workDir); }
    static void option(Step& step, const ToolOption& o) {
        step.arguments.push_back(o.first);
        if (!o.second.empty()) step.arguments.push_back(o.second);  // else a flag
    }
    // An output, named on the command line after `option` (none for a positional argument).
    void output(Step& step, const std::string& option, const fs::path& path) const {
        if (!option.empty()) step.arguments.push_back(option);
        step.arguments.push_back(show(path));
        step.outputs.push_back(path);
    }
    void input(Step& step, const std::string& option, const fs::path& path) const {
        if (!option.empty()) step.arguments.push_back(option);
        step.arguments.push_back(show(path));
        step.inputs.push_back(path);
    }
    // An outside renderer's command after --, last (vri-outside, vri-verify); its files key the step's cache.
    static void rendererCommand(Step& step, const std::vector<std::string>& command, const std::string& name,
                                const std::string& image, const std::string& timeout, const std::vector<fs::path>& files) {
        if (command.empty()) return;
        step.arguments.insert(step.arguments.end(),
                              {outside_flag::rendererImage, image, outside_flag::rendererName, name});
        if (!timeout.empty()) step.arguments.insert(step.arguments.end(), {outside_flag::timeout, timeout});
        step.arguments.push_back("--");
        step.arguments.insert(step.arguments.end(), command.begin(), command.end());
        step.inputs.insert(step.inputs.end(), files.begin(), files.end());
        step.parameters.emplace_back("renderer", name);
    }
    bool written(const fs::path& path) const {  // by a step planned so far
        return std::any_of(plan_.steps.begin(), plan_.steps.end(), [&](const Step& s) {
            return std::find(s.outputs.begin(), s.outputs.end(), path) != s.outputs.end();
        });
    }

    const Experiment& experiment_;
    Plan& plan_;
};

void Planner::sceneOptions(Step& step, const SceneSpec& scene) const {
    step.parameters.emplace_back("scene", scene.name);
    if (!scene.dataset.empty()) step.parameters.emplace_back("dataset", scene.dataset);
    for (const ToolOption& o : scene.options) {
        const bool isFile = o.first == scene_flag::volume || o.first == scene_flag::tf;
        if (isFile)
            input(step, o.first, o.second);
        else
            option(step, o);
    }
    step.inputs.insert(step.inputs.end(), scene.dataFiles.begin(), scene.dataFiles.end());
}

void Planner::addRender(const RunSpec& run) {
    const SceneSpec& scene = experiment_.scene(run.scene);
    Step step{run.id, "render", run.tool, {}, {}, {}, {}};
    sceneOptions(step, scene);
    step.pixels = static_cast<std::uint64_t>(scene.width) * static_cast<std::uint64_t>(scene.height);
    // A tile loads the whole volume too; a brick replaces this with its own box.
    if (scene.volumeShape) step.volumeBytes = heldBytes(*scene.volumeShape, {{0, 0, 0}, scene.volumeShape->dims});
    for (const ToolOption& o : run.options) option(step, o);
    step.parameters.insert(step.parameters.end(), run.parameters.begin(), run.parameters.end());
    step.arguments.push_back("-q");  // vri-run shows its own progress
    step.alone = run.tiles == 1 && run.bricks == glm::ivec3(1);
    if (run.bricks != glm::ivec3(1)) {  // each brick's layer in tiles where the run has tiles too
        addBricks(run, scene, step);
        return;
    }
    if (run.tiles > 1) {
        addTiles(run, scene, step);
        return;
    }
    output(step, "-o", renderImage(plan_, run.id));
    output(step, render_flag::png, result(run.id + ".png"));
    output(step, render_flag::stats, result(run.id + ".json"));
    if (std::ranges::any_of(run.parameters, [](auto& kv) { return kv.first == "log_ray"; }))
        output(step, render_flag::log, result(run.id + "-ray.csv"));
    rendererCommand(step, run.command, run.rendererName, run.rendererImage, run.rendererTimeout, run.commandFiles);
    plan_.steps.push_back(std::move(step));
}

// The run's image as tiles: one step per band of rows (the render's command with --region), then
// vri-merge-tiles writing the files the untiled step writes, so that everything downstream reads the same.
void Planner::addTiles(const RunSpec& run, const SceneSpec& scene, const Step& render) {
    std::vector<RunPart> parts;
    const std::vector<PixelRegion> bands = rowBands(scene.width, scene.height, run.tiles);
    for (std::size_t k = 0; k < bands.size(); ++k)
        parts.push_back({".tile-" + std::to_string(k + 1),
                         {kRegionFlag, bands[k].text()},
                         {"region", bands[k].text()},
                         static_cast<std::uint64_t>(bands[k].width) * static_cast<std::uint64_t>(bands[k].height),
                         1,
                         render.volumeBytes});
    addSplit(run, scene, render, merge_flag::tile, {"tiles", std::to_string(run.tiles)}, parts);
}

// The run's volume as bricks: one step per brick (the render's command with --bricks and --brick) writing
// its layer, then vri-merge-tiles --layer writing the files the unbricked step writes.
void Planner::addBricks(const RunSpec& run, const SceneSpec& scene, const Step& render) {
    std::vector<RunPart> parts;
    const std::string grid = brickText(run.bricks);
    // Where a brick reads its box alone (SceneSpec::volumeShape), each brick's stored box.
    std::optional<BrickGrid> bricks;
    if (scene.volumeShape) try {
            bricks = BrickGrid(scene.volumeShape->dims, run.bricks);
        } catch (const Error&) {  // a grid finer than the volume: vri-render says so
        }
    const auto brickBytes = [&](glm::ivec3 brick) -> std::uint64_t {
        return bricks ? heldBytes(*scene.volumeShape, bricks->storedBox(brick)) : 0;
    };
    for (int z = 0; z < run.bricks.z; ++z)
        for (int y = 0; y < run.bricks.y; ++y)
            for (int x = 0; x < run.bricks.x; ++x)
                parts.push_back({".brick-" + std::to_string(x) + "-" + std::to_string(y) + "-" + std::to_string(z),
                                 {scene_flag::bricks, grid, scene_flag::brick, brickText({x, y, z})},
                                 {"brick", brickText({x, y, z})},
                                 render.pixels,
                                 run.bricks.x * run.bricks.y * run.bricks.z,
                                 brickBytes({x, y, z})});
    addSplit(run, scene, render, merge_flag::layer, {"bricks", grid}, parts);
}

void Planner::addSplit(const RunSpec& run, const SceneSpec& scene, const Step& render, const char* mergeFlag,
                       const std::pair<std::string, std::string>& mergeParameter, const std::vector<RunPart>& parts) {
    Step merge{run.id, "render", "vri-merge-tiles", {}, {}, {}, render.parameters};
    merge.parameters.push_back(mergeParameter);
    merge.pixels = render.pixels;  // it holds the whole image (and reads every part's)
    for (const RunPart& part : parts) {
        Step step = render;
        step.id = run.id + part.suffix;
        step.pixels = part.pixels;
        step.volumeParts = part.volumeParts;
        step.volumeBytes = part.volumeBytes;
        step.arguments.insert(step.arguments.end(), part.arguments.begin(), part.arguments.end());
        step.parameters.push_back(part.parameter);
        merge.arguments.push_back(mergeFlag);
        input(merge, "", result(step.id + ".exr"));
        input(merge, "", result(step.id + ".json"));
        if (mergeFlag == std::string_view(merge_flag::layer) && run.tiles > 1) {
            addLayerTiles(run, scene, step);
            continue;
        }
        output(step, "-o", result(step.id + ".exr"));
        output(step, render_flag::stats, result(step.id + ".json"));
        plan_.steps.push_back(std::move(step));
    }
    for (const ToolOption& o : scene.options)  // the preview's looks, made from the whole image
        if (o.first == scene_flag::pngInvert || o.first == scene_flag::pngExposure || o.first == scene_flag::background)
            option(merge, o);
    output(merge, "-o", renderImage(plan_, run.id));
    output(merge, render_flag::png, result(run.id + ".png"));
    output(merge, render_flag::stats, result(run.id + ".json"));
    plan_.steps.push_back(std::move(merge));
}

// A brick's layer as tiles: the brick's command with --region per band of rows, then vri-merge-tiles --tile
// writing the layer the brick's step would have, which the join then reads.
void Planner::addLayerTiles(const RunSpec& run, const SceneSpec& scene, const Step& brick) {
    Step merge{brick.id, "render", "vri-merge-tiles", {}, {}, {}, brick.parameters};
    merge.parameters.push_back({"tiles", std::to_string(run.tiles)});
    merge.pixels = brick.pixels;
    const std::vector<PixelRegion> bands = rowBands(scene.width, scene.height, run.tiles);
    for (std::size_t k = 0; k < bands.size(); ++k) {
        Step tile = brick;
        tile.id = brick.id + ".tile-" + std::to_string(k + 1);
        tile.pixels = static_cast<std::uint64_t>(bands[k].width) * static_cast<std::uint64_t>(bands[k].height);
        tile.arguments.insert(tile.arguments.end(), {kRegionFlag, bands[k].text()});
        tile.parameters.push_back({"region", bands[k].text()});
        output(tile, "-o", result(tile.id + ".exr"));
        output(tile, render_flag::stats, result(tile.id + ".json"));
        merge.arguments.push_back(merge_flag::tile);
        input(merge, "", result(tile.id + ".exr"));
        input(merge, "", result(tile.id + ".json"));
        plan_.steps.push_back(std::move(tile));
    }
    output(merge, "-o", result(brick.id + ".exr"));
    output(merge, render_flag::stats, result(brick.id + ".json"));
    plan_.steps.push_back(std::move(merge));
}

void Planner::addDiff(const ComparisonSpec& c) {
    Step step{c.id, "diff", "vri-diff", {}, {}, {}, {{"reference", c.reference}, {"run", c.run}}};
    input(step, "", renderImage(plan_, c.reference));
    input(step, "", renderImage(plan_, c.run));
    step.arguments.insert(step.arguments.end(), {diff_flag::threshold, commaList(c.thresholds)});
    // Measure only: a difference is the result here, not a failure of the step.
    step.arguments.insert(step.arguments.end(), {diff_flag::failPercent, "100", diff_flag::warnPercent, "100"});
    output(step, diff_flag::json, result(c.id + ".json"));
    if (!c.diffImage.empty()) output(step, diff_flag::diffImage, result(c.id + "." + c.diffImage));
    if (!c.diffScale.empty()) step.arguments.insert(step.arguments.end(), {diff_flag::diffScale, c.diffScale});
    if (!c.heatScale.empty()) step.arguments.insert(step.arguments.end(), {diff_flag::heatScale, c.heatScale});
    if (!c.heatTop.empty()) step.arguments.insert(step.arguments.end(), {diff_flag::heatTop, c.heatTop});
    if (c.heatSigned) step.arguments.push_back(diff_flag::heatSigned);
    // One scale for the set, computed once: the set's first comparison takes the largest error over every run
    // (--scale-over), the others read it from its JSON (--scale-from); each reading every image would cost the
    // square of the set's size in image reads (56 Bonsai maps of paper-b-cpu: 3,136 reads, 116 s).
    if (c.sharedScale) {
        const auto first = std::ranges::find_if(experiment_.comparisons, [&](auto& o) { return o.group == c.group; });
        if (first->id == c.id) {
            for (const ComparisonSpec& other : experiment_.comparisons)
                if (other.group == c.group && other.id != c.id)
                    input(step, diff_flag::scaleOver, renderImage(plan_, other.run));
        } else {
            input(step, diff_flag::scaleFrom, result(first->id + ".json"));
        }
    }
    if (!c.mask.empty()) {
        if (parseMaskSpec(c.mask).kind == MaskSpec::Kind::Image)
            input(step, diff_flag::mask, c.mask);
        else
            step.arguments.insert(step.arguments.end(), {diff_flag::mask, c.mask});
    }
    if (c.histogram) output(step, diff_flag::histogram, result(c.id + "-histogram.csv"));
    plan_.steps.push_back(std::move(step));
}

void Planner::addCommand(const CommandSpec& command) {
    Step step{command.name, "command", command.tool, {}, {}, {}, {{"command", command.name}}};
    step.alone = true;
    if (!command.scene.empty()) sceneOptions(step, experiment_.scene(command.scene));
    for (const ToolOption& o : command.options) option(step, o);
    step.threads = command.threads;
    step.pixels = command.pixels;
    for (const auto& [word, path] : command.inputs) input(step, word, path);
    for (const auto& [word, file] : command.outputs) output(step, word, result(file));
    rendererCommand(step, command.command, command.rendererName, command.rendererImage, command.rendererTimeout,
                    command.commandFiles);
    plan_.steps.push_back(std::move(step));
}

// A convergence table's point: the run's series (its id without the swept step, "-h0.5") and its step,
// "-" for a run without one (the exact method).
std::pair<std::string, std::string> convergenceSeries(const RunSpec& run) {
    const auto step = std::ranges::find(run.parameters, std::string("step"), &std::pair<std::string, std::string>::first);
    if (step == run.parameters.end()) return {run.id, "-"};
    std::string series = run.id;
    if (const std::size_t at = series.find("-h" + step->second); at != std::string::npos)
        series.erase(at, step->second.size() + 2);
    return {series, step->second};
}

void Planner::addTable(const TableSpec& table) {
    Step step{"table-" + table.name, "table", "vri-tabulate", {}, {}, {}, {{"table", table.name}}};
    if (table.layout == "convergence") {
        step.arguments = {tabulate_flag::layout, table.layout, tabulate_flag::title, table.title};
        for (const std::string& group : table.comparisons)
            for (const ComparisonSpec& c : experiment_.comparisons)
                if (c.group == group) {
                    const auto [series, h] = convergenceSeries(experiment_.run(c.run));
                    step.arguments.insert(step.arguments.end(), {tabulate_flag::point, series, h});
                    input(step, "", result(c.id + ".json"));
                    input(step, "", result(c.run + ".json"));  // an error bound, where the run has one
                }
        output(step, tabulate_flag::points, result(table.name + "-points.csv"));
    } else if (table.layout != "matrix") {
        const bool tradeoff = table.layout == "tradeoff";
        step.arguments = {tabulate_flag::layout, table.layout, tabulate_flag::title, table.title};
        if (tradeoff) {
            step.arguments.insert(step.arguments.end(), {tabulate_flag::threshold, commaList(table.thresholds)});
            if (!table.baseline.empty())
                step.arguments.insert(step.arguments.end(), {tabulate_flag::baseline, table.baseline});
            if (table.channels != "all")
                step.arguments.insert(step.arguments.end(), {tabulate_flag::channels, table.channels});
        }
        if (table.rows.empty()) {  // one row per compared run
            for (const std::string& group : table.comparisons)
                for (const ComparisonSpec& c : experiment_.comparisons)
                    if (c.group == group) {
                        step.arguments.insert(step.arguments.end(),
                                              {tradeoff ? tabulate_flag::run : tabulate_flag::row, c.run});
                        if (tradeoff) input(step, "", result(c.run + ".json"));  // its time: the run's stats
                        input(step, "", result(c.id + ".json"));
                    }
        }
        for (const auto& [label, runs] : table.rows) {  // the reader checked that each run is compared once
            step.arguments.insert(step.arguments.end(), {tabulate_flag::row, label});
            for (const std::string& run : runs) {
                const auto c = std::ranges::find_if(experiment_.comparisons, [&](const ComparisonSpec& x) {
                    return x.run == run && std::ranges::count(table.comparisons, x.group) > 0;
                });
                input(step, "", result(c->id + ".json"));
            }
        }
    } else {
        step.arguments = {tabulate_flag::layout, "matrix",   tabulate_flag::title, table.title,
                          tabulate_flag::value,  table.value};
        for (const std::string& run : table.runs) {
            const std::string& scene = experiment_.run(run).scene;
            const bool prefixed = run.starts_with(scene + "-");
            if (table.byScene)
                step.arguments.insert(step.arguments.end(),
                                      {tabulate_flag::cell, prefixed ? run.substr(scene.size() + 1) : run, scene});
            else
                step.arguments.insert(step.arguments.end(), {tabulate_flag::cell, run, table.column});
            input(step, "", result(run + ".json"));
        }
    }
    if (!table.precision.empty())
        step.arguments.insert(step.arguments.end(), {tabulate_flag::precision, table.precision});
    output(step, "-o", result(table.name + ".md"));
    output(step, tabulate_flag::csv, result(table.name + ".csv"));
    plan_.steps.push_back(std::move(step));
}

void Planner::addFigure(const FigureSpec& figure) {
    Step step{"figure-" + figure.name, "figure", "vri-plot", {}, {}, {}, {{"figure", figure.name}}};
    input(step, "", figure.spec);
    // The spec names its data relative to --data-dir, so one spec serves full and quick results alike.
    step.arguments.insert(step.arguments.end(), {plot_flag::dataDir, show(plan_.resultsDir)});
    for (const std::string& file : figure.data) {
        const fs::path path = result(file);
        if (!written(path))
            throw Error(figure.dataAt + ": figure '" + figure.name + "' reads '" + file + "', which no step writes");
        step.inputs.push_back(path);
    }
    // What the spec itself names is read too, wherever it lies (another experiment's results): the step's
    // key and record cover it, and a step of this run that writes it runs first.
    for (const fs::path& path : plotDataFiles(figure.spec, plan_.resultsDir))
        if (std::find(step.inputs.begin(), step.inputs.end(), path) == step.inputs.end()) step.inputs.push_back(path);
    output(step, "-o", result(figure.name + ".png"));
    step.outputs.push_back(result(figure.name + ".svg"));  // vri-plot writes these beside the PNG
    step.outputs.push_back(result(figure.name + ".gp"));
    plan_.steps.push_back(std::move(step));
}

}  // namespace

const Step& Plan::step(const std::string& id) const {
    for (const Step& s : steps)
        if (s.id == id) return s;
    throw Error("no step '" + id + "' in the plan");
}

std::string Plan::commandPath(const fs::path& file) const { return displayPath(file, workDir); }

std::vector<PixelRegion> rowBands(int width, int height, int n) {
    std::vector<PixelRegion> bands;
    for (int k = 0; k < n; ++k) {
        // Rows [k H / n, (k + 1) H / n): heights differ by at most one, the taller bands last.
        const int y0 = static_cast<int>(std::int64_t(k) * height / n);
        const int y1 = static_cast<int>(std::int64_t(k + 1) * height / n);
        bands.push_back({0, y0, width, y1 - y0});
    }
    return bands;
}

fs::path renderImage(const Plan& plan, const std::string& runId) { return plan.resultsDir / (runId + ".exr"); }

Plan planExperiment(const Experiment& experiment, const fs::path& resultsDir, const fs::path& workDir) {
    Plan plan{normalDirectory(resultsDir), normalDirectory(workDir), {}, {}};
    Planner planner(experiment, plan);
    for (const RunSpec& run : experiment.runs) planner.addRender(run);
    for (const ComparisonSpec& c : experiment.comparisons) planner.addDiff(c);
    for (const CommandSpec& c : experiment.commands) planner.addCommand(c);
    for (const TableSpec& t : experiment.tables) planner.addTable(t);
    for (const FigureSpec& f : experiment.figures) planner.addFigure(f);

    std::map<fs::path, std::size_t> writer;
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        const Step& step = plan.steps[i];
        if (std::count_if(plan.steps.begin(), plan.steps.end(), [&](const Step& s) { return s.id == step.id; }) > 1)
            throw Error(experiment.source.string() + ": two steps are called '" + step.id + "'");
        // The reader holds every name to isSafeName; this holds the plan to what that buys: each step's
        // record and outputs in the experiment's folder, whatever made the Experiment.
        if (!isSafeName(step.id))
            throw Error(experiment.source.string() + ": step id '" + step.id + "' is not a safe name");
        for (const fs::path& out : step.outputs)
            if (out.parent_path() != plan.resultsDir)
                throw Error(experiment.source.string() + ": step '" + step.id + "' would write " + out.string() +
                            ", outside the experiment's folder " + plan.resultsDir.string());
        std::vector<std::size_t> dependencies;
        for (const fs::path& in : step.inputs)
            if (auto w = writer.find(in); w != writer.end() && std::find(dependencies.begin(), dependencies.end(), w->second) == dependencies.end())
                dependencies.push_back(w->second);
        for (const fs::path& out : step.outputs)
            if (!writer.emplace(out, i).second)
                throw Error(experiment.source.string() + ": steps '" + plan.steps[writer[out]].id + "' and '" + step.id +
                            "' both write " + out.string());
        plan.dependencies.push_back(std::move(dependencies));
    }
    return plan;
}

std::vector<std::string> commandWords(const Plan& plan, const Step& step, const fs::path& toolDir) {
    std::string tool = displayPath(fs::absolute(toolDir / step.tool).lexically_normal(), plan.workDir);
    if (tool.find('/') == std::string::npos) tool = "./" + tool;  // a bare name would be looked up in PATH
    std::vector<std::string> words{tool};
    words.insert(words.end(), step.arguments.begin(), step.arguments.end());
    return words;
}

std::string shellCommand(const std::vector<std::string>& words) {
    std::string line;
    for (const std::string& word : words) line.append(line.empty() ? "" : " ").append(shellQuote(word));
    return line;
}

}  // namespace vri
