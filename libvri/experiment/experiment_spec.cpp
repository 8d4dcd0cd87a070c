// Reading experiment files: validation with file:line:col in every message, quick: overrides and
// the expansion of parameter sweeps into runs.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>

#include "libvri/core/brick_grid.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/render_option_table.h"
#include "libvri/core/transfer_function.h"
#include "libvri/experiment/datasets.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"

#include "libvri/core/heat_map.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/core/scene_flags.h"
#include "libvri/experiment/experiment_keys.h"
#include "libvri/experiment/timing_defaults.h"
#include "libvri/io/volume_io.h"
#include "libvri/io/volume_read_options.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/io/transfer_function_yaml_node.h"
#include "libvri/io/yaml_util.h"
#include "libvri/render/outside_renderer.h"
#include "libvri/render/stats_schema.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/format.h"
#include "libvri/util/parse.h"
#include "libvri/util/printable.h"
#include "libvri/util/process.h"
#include "libvri/util/utf8.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// `method: exact` is vri-reference's accurate solution (a reference, not a vri-render method).
constexpr std::string_view kExactMethod = "exact";

// The options with which vri tools write a file: in `commands:` they belong under `outputs:`, where
// the file lands in the results folder, never under `options:` or `inputs:` (an input named `o`
// would be overwritten wherever it is). A tool with a new output option adds it here.
const std::set<std::string, std::less<>> kOutputOptions = {
    "-o",        "--output",      "--png",       "--stats",      "--json",       "--csv",
    "--log",     "--diff-image",  "--histogram", "--errors",     "--errors-csv", "--convergence",
    "--diagram", "--field-image", "--summary",   "--error-image"};

// Whether a command's option value names a file, which `options:` must not (a tool may write to it,
// relative to where vri-run runs): a path, or a name with a file extension vri reads or writes. A
// value that reads as another option ("-o", "--csv") would shift the words after it, so it counts too.
bool namesFile(const std::string& value) {
    static const std::set<std::string, std::less<>> extensions = {".vdb", ".nhdr", ".nrrd", ".dat", ".raw", ".exr",
                                                                  ".png", ".svg",  ".gp",   ".csv", ".md",  ".json",
                                                                  ".txt", ".yaml", ".yml",  ".log"};
    std::string ext = fs::path(value).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool looksLikeOption =
        value.size() > 1 && value[0] == '-' && !(std::isdigit(static_cast<unsigned char>(value[1])) || value[1] == '.');
    return value.find('/') != std::string::npos || value == "." || value == ".." || value.starts_with("~") ||
           extensions.contains(ext) || looksLikeOption;
}

// How a tool's option is named on its command line: "-o" for a one-letter key, "--summary" otherwise.
std::string optionWord(const std::string& key) { return (key.size() == 1 ? "-" : "--") + key; }

// Reads experiment files; `source` names the file in messages, `baseDir` resolves relative paths.
class ExperimentReader {
public:
    ExperimentReader(std::string source, fs::path baseDir) : source_(std::move(source)), baseDir_(std::move(baseDir)) {}

    Experiment read(YAML::Node root, bool quick);

private:
    std::string at(const YAML::Node& node) const { return yaml::where(source_, node); }
    // A text of the file; UTF-8, as the manifest that will hold it is JSON: refused at its line, not after
    // the work whose record it would break.
    std::string text(const YAML::Node& node, std::string_view what) const {
        std::string value = yaml::toString(node, source_, what);
        if (const std::optional<std::size_t> bad = firstInvalidUtf8(value))
            throw Error(at(node) + ": " + std::string(what) + ": not UTF-8 at byte " + std::to_string(*bad) + " ('" +
                        escapeInvalidUtf8(value.substr(0, 60)) + "')");
        return value;
    }
    std::string number(const YAML::Node& node, std::string_view what) const {
        yaml::toDouble(node, source_, what);
        return node.Scalar();
    }
    bool flag(const YAML::Node& node, std::string_view what) const { return yaml::toBool(node, source_, what); }
    std::string vec3(const YAML::Node& node, std::string_view what) const;
    std::vector<std::string> names(const YAML::Node& node, std::string_view what) const;
    fs::path existingFile(const YAML::Node& node, std::string_view what) const;
    YAML::Node required(const YAML::Node& map, const char* key, std::string_view what) const;
    // Items of a name -> entry mapping, each checked to be a mapping, in file order.
    std::vector<std::pair<std::string, YAML::Node>> entries(const YAML::Node& node, std::string_view what) const;
    // Items of an option -> value mapping of a command, keys checked to be option names, in file order.
    std::vector<std::pair<std::string, YAML::Node>> optionEntries(const YAML::Node& node, std::string_view what) const;
    std::optional<std::string> optionValue(const YAML::Node& node, const std::string& key) const;
    std::string resultFile(const YAML::Node& node, const std::string& key) const;
    void requireRun(const Experiment& experiment, const std::string& id, const YAML::Node& where) const;

    PaperItem readPaper(const YAML::Node& node) const;
    // Every required key of the experiment, its paper and its scenes that the file lacks, in one error: a
    // first file then fails once, not once per key. (Comparisons, commands and figures name a missing key
    // after their unknown keys, which are the likelier mistake there: a misspelt required key.)
    void requireAllKeys(const YAML::Node& root) const;
    SceneSpec readScene(const std::string& name, const YAML::Node& node);
    // `renderers:`: outside renderers by name, each a command (a list of words with vri-outside's
    // placeholders) and the image format it writes; methods name them with `renderer:`.
    void readRenderers(const YAML::Node& node);
    void readRuns(const YAML::Node& node, bool reference, Experiment& experiment) const;
    void readComparisons(const YAML::Node& node, Experiment& experiment) const;
    void readCommands(const YAML::Node& node, Experiment& experiment) const;
    void readTables(const YAML::Node& node, Experiment& experiment) const;
    void readFigures(const YAML::Node& node, Experiment& experiment) const;
    void readReproduce(const YAML::Node& node, Experiment& experiment) const;

    std::string source_;
    fs::path baseDir_;
    std::vector<std::string> defaults_;  // Experiment::defaults
    std::optional<std::vector<DatasetInfo>> catalog_;  // experiments/datasets.yaml, read when a scene names a dataset
    struct Renderer {
        std::vector<std::string> command;
        std::string image;
        std::string timeout;          // seconds, as written; empty: no limit
        std::vector<fs::path> files;  // the executable, then every word that names an existing file
    };
    std::map<std::string, Renderer, std::less<>> renderers_;
};

std::string ExperimentReader::vec3(const YAML::Node& node, std::string_view what) const {
    if (!node.IsSequence() || node.size() != 3) throw Error(at(node) + ": " + std::string(what) + " must be [x, y, z]");
    return number(node[0], what) + "," + number(node[1], what) + "," + number(node[2], what);
}

std::vector<std::string> ExperimentReader::names(const YAML::Node& node, std::string_view what) const {
    if (node.IsScalar()) return {node.Scalar()};
    if (!node.IsSequence()) throw Error(at(node) + ": " + std::string(what) + " must be a name or a list of names");
    std::vector<std::string> result;
    for (const YAML::Node& item : node) result.push_back(text(item, what));
    return result;
}

fs::path ExperimentReader::existingFile(const YAML::Node& node, std::string_view what) const {
    const fs::path path = (baseDir_ / text(node, what)).lexically_normal();
    if (!fs::exists(path)) throw Error(at(node) + ": " + std::string(what) + ": no such file: " + path.string());
    if (!fs::is_regular_file(path))  // a device, a FIFO, a folder: read by steps later, or never ending
        throw Error(at(node) + ": " + std::string(what) + ": " + path.string() + " is not a regular file");
    return fs::absolute(path);
}

YAML::Node ExperimentReader::required(const YAML::Node& map, const char* key, std::string_view what) const {
    const YAML::Node node = map[key];
    if (!node) throw Error(at(map) + ": " + std::string(what) + " has no '" + key + "'");
    return node;
}

std::vector<std::pair<std::string, YAML::Node>> ExperimentReader::entries(const YAML::Node& node,
                                                                          std::string_view what) const {
    yaml::requireMap(node, source_, what);
    std::vector<std::pair<std::string, YAML::Node>> result;
    for (const auto& kv : node) {
        const std::string name = text(kv.first, std::string(what) + " name");
        if (!isSafeName(name))
            throw Error(at(kv.first) + ": " + std::string(what) + ": a name must be " + std::string(kSafeName));
        yaml::requireMap(kv.second, source_, std::string(what) + " '" + name + "'");
        result.emplace_back(name, kv.second);
    }
    return result;
}

std::vector<std::pair<std::string, YAML::Node>> ExperimentReader::optionEntries(const YAML::Node& node,
                                                                                std::string_view what) const {
    yaml::requireMap(node, source_, what);
    std::vector<std::pair<std::string, YAML::Node>> result;
    for (const auto& kv : node) {
        const std::string key = text(kv.first, std::string(what) + " key");
        // Letters, digits and '-' only: a key is one word of the command and cannot pass as `--`.
        static constexpr std::string_view allowed = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-";
        if (key.empty() || key.front() == '-' || key.find_first_not_of(allowed) != std::string::npos)
            throw Error(at(kv.first) + ": '" + key + "' is not an option name (letters, digits and '-')");
        result.emplace_back(key, kv.second);
    }
    return result;
}

// A value as the file spells it, a list joined by commas, "" (a flag) for true, nothing for false.
// Only a plain true or false is a flag: a quoted "true" is the word.
std::optional<std::string> ExperimentReader::optionValue(const YAML::Node& node, const std::string& key) const {
    const std::string expected = "option '" + key + "' must be a value, a list of values, true or false";
    if (node.IsSequence()) {
        if (node.size() == 0) throw Error(at(node) + ": option '" + key + "': an empty list");
        std::string joined;
        for (const YAML::Node& item : node) {
            if (!item.IsScalar() || item.Scalar().empty()) throw Error(at(item) + ": " + expected);
            joined += (joined.empty() ? "" : ",") + item.Scalar();
        }
        return joined;
    }
    if (!node.IsScalar() || node.Scalar().empty()) throw Error(at(node) + ": " + expected);
    if (node.Tag() == "?" && (node.Scalar() == "true" || node.Scalar() == "false"))
        return node.Scalar() == "true" ? std::optional<std::string>("") : std::nullopt;
    return node.Scalar();
}

// A file name in the results folder: no folders, not hidden (.steps), not one of vri-run's own files.
std::string ExperimentReader::resultFile(const YAML::Node& node, const std::string& key) const {
    const std::string name = text(node, "output '" + key + "'");
    if (!isSafeName(name) || name == "manifest.json" || name == "reproduce.json")
        throw Error(at(node) + ": output '" + key + "' must be a file name in the results folder (" +
                    std::string(kSafeName) + "; not manifest.json or reproduce.json)");
    return name;
}

void ExperimentReader::requireRun(const Experiment& experiment, const std::string& id, const YAML::Node& where) const {
    if (std::none_of(experiment.runs.begin(), experiment.runs.end(), [&](const RunSpec& r) { return r.id == id; }))
        throw Error(at(where) + ": unknown run '" + id + "'");
}

PaperItem ExperimentReader::readPaper(const YAML::Node& node) const {
    yaml::requireMap(node, source_, "paper");
    yaml::requireKeys(node, source_, kPaperKeys);
    PaperItem paper{text(required(node, "paper", "paper"), "paper.paper"), "", ""};
    if (paper.paper != "A" && paper.paper != "B" && paper.paper != "none")
        throw Error(at(node["paper"]) + ": paper.paper must be A, B or none, got '" + paper.paper + "'");
    if (paper.paper != "none" || node["item"]) paper.item = text(required(node, "item", "paper"), "paper.item");
    if (paper.paper != "none" || node["says"]) paper.says = text(required(node, "says", "paper"), "paper.says");
    return paper;
}

void ExperimentReader::requireAllKeys(const YAML::Node& root) const {
    std::vector<std::string> missing;
    const auto need = [&](const YAML::Node& map, const char* key, const std::string& what) {
        if (!map[key]) missing.push_back(at(map) + ": " + what + " has no '" + key + "'");
    };
    const auto eachEntry = [](const YAML::Node& node, const auto& visit) {
        if (node && node.IsMap())
            for (const auto& kv : node)
                if (kv.second.IsMap()) visit(kv.first.Scalar(), kv.second);
    };
    need(root, "name", "the experiment");
    if (const YAML::Node paper = root["paper"]; paper && paper.IsMap()) {
        need(paper, "paper", "paper");
        if (paper["paper"] && paper["paper"].Scalar() != "none") {
            need(paper, "item", "paper");
            need(paper, "says", "paper");
        }
    }
    if (root["scenes"] || root["methods"] || root["references"] || !root["commands"]) {
        need(root, "scenes", "the experiment");
        need(root, "methods", "the experiment");
    }
    eachEntry(root["scenes"], [&](const std::string& name, const YAML::Node& scene) {
        if (!scene["dataset"] && !scene["volume"] && !scene["field"])
            missing.push_back(at(scene) + ": scene '" + name + "' has none of 'volume', 'dataset' or 'field'");
        need(scene, "tf", "scene '" + name + "'");
    });
    if (missing.empty()) return;
    std::string message = missing.size() == 1 ? "" : std::to_string(missing.size()) + " required keys missing: ";
    for (std::size_t i = 0; i < missing.size(); ++i) message += (i ? "; " : "") + missing[i];
    throw Error(message);
}

SceneSpec ExperimentReader::readScene(const std::string& name, const YAML::Node& node) {
    yaml::requireKeys(node, source_, kSceneKeys);
    SceneSpec scene{name, {}, {}, {}, {}, {}};
    const std::string what = "scene '" + name + "'";
    const int inputs = !!node["dataset"] + !!node["volume"] + !!node["field"];
    if (inputs != 1) throw Error(at(node) + ": " + what + " needs exactly one of dataset, volume or field");
    if (const YAML::Node n = node["dataset"]) {
        scene.dataset = text(n, "dataset");
        const fs::path catalog = baseDir_ / "datasets.yaml";
        if (!catalog_ && !fs::exists(catalog))
            throw Error(at(n) + ": dataset '" + scene.dataset + "': no catalog " + catalog.string() +
                        " beside the experiment (dataset: names an entry of the repository's experiments/datasets.yaml; "
                        "elsewhere name the file with volume: PATH, relative to the experiment or to $VRI_DATA_DIR)");
        if (!catalog_) catalog_ = loadDatasetCatalog(catalog);
        const DatasetInfo& info = findDataset(*catalog_, scene.dataset, at(n) + " (volume: PATH names any other file)");
        scene.datasetStatus = info.status;
        scene.datasetNote = info.note;
        const fs::path file = fs::absolute(datasetPath(info, defaultDataDir())).lexically_normal();
        if (!fs::is_regular_file(file))
            throw Error(at(n) + ": dataset '" + scene.dataset + "': no such file: " + file.string() +
                        " (the volumes are looked up in $VRI_DATA_DIR, " +
                        (std::getenv("VRI_DATA_DIR") ? "set" : "not set: ../shared/data/volumes") +
                        "; make data downloads them)");
        scene.files.push_back(file);
        scene.options.emplace_back(scene_flag::volume, file.string());
        if (info.header.empty()) {
            const RawLayout layout = rawLayout(info);
            scene.volumeShape = VolumeShape{layout.dims, layout.type};
            // Exactly as the catalog has them: a spacing printed to 6 digits would be another volume.
            const auto join = [](auto v) { return exactNumber(v.x) + "," + exactNumber(v.y) + "," + exactNumber(v.z); };
            scene.options.emplace_back(scene_flag::dims, join(layout.dims));
            scene.options.emplace_back(scene_flag::type, std::string(voxelTypeName(layout.type)));
            scene.options.emplace_back(scene_flag::byteOrder, layout.order == ByteOrder::Big ? "big" : "little");
            scene.options.emplace_back(scene_flag::spacing, join(layout.spacing));
        }
    } else if (const YAML::Node n = node["volume"]) {
        const fs::path path = text(n, "volume");
        const std::optional<fs::path> file = findVolume(path, baseDir_);
        if (!file)
            throw Error(at(n) + ": volume: no such file: " + (baseDir_ / path).lexically_normal().string() +
                        (path.is_relative() ? " nor " + (defaultDataDir() / path).lexically_normal().string() +
                                                  " ($VRI_DATA_DIR" + (std::getenv("VRI_DATA_DIR") ? "" : ", not set") + ")"
                                            : ""));
        scene.files.push_back(*file);
        scene.options.emplace_back(scene_flag::volume, scene.files.back().string());
        for (const fs::path& read : filesReadBy(*file))
            if (read != *file) scene.dataFiles.push_back(fs::absolute(read).lexically_normal());
        try {
            scene.volumeShape = brickedShape(*file);  // a raw file's by its name, a header's, a TIFF stack's
        } catch (const Error&) {  // a type vri does not read, a broken header: vri-render says so
        }
    } else {
        const std::string field = text(node["field"], "field");
        if (field != "linear") throw Error(at(node["field"]) + ": unknown analytic field '" + field + "' (expected linear)");
        scene.options.emplace_back(scene_flag::field, field);
        if (const YAML::Node dims = node["field_dims"]) {
            const std::string d = vec3(dims, "field_dims");
            for (const YAML::Node& v : dims)
                if (double x = v.as<double>(); x != std::floor(x) || x < 2)
                    throw Error(at(v) + ": field_dims must be whole numbers >= 2");
            scene.options.emplace_back(scene_flag::fieldDims, d);
        }
        if (node["as_grid"] && flag(node["as_grid"], "as_grid"))
            scene.options.emplace_back(scene_flag::fieldAsGrid, "");
    }
    if ((node["field_dims"] || node["as_grid"]) && !node["field"])
        throw Error(at(node) + ": field_dims and as_grid apply to analytic fields only");

    if (const YAML::Node convention = node["convention"]) {
        parseGridConvention(text(convention, "convention"), at(convention) + ": convention");
        scene.options.emplace_back(scene_flag::convention, convention.Scalar());
    } else {  // written into the commands all the same, so that a command read alone says it
        const std::string name(gridConventionName(kDefaultConvention));
        scene.options.emplace_back(scene_flag::convention, name);
        defaults_.push_back(what + ": convention " + name + ", the tools' default");
    }

    const YAML::Node tf = required(node, "tf", what);
    scene.files.push_back(existingFile(tf, "tf"));
    loadTransferFunction(scene.files.back());  // its own errors carry its own file:line:col
    scene.options.emplace_back(scene_flag::tf, scene.files.back().string());

    if (const YAML::Node size = node["size"]) {
        if (!size.IsSequence() || size.size() != 2) throw Error(at(size) + ": size must be [width, height]");
        int wh[2];
        for (std::size_t i = 0; i < 2; ++i)
            wh[i] = static_cast<int>(yaml::toWholeNumber(size[i], source_, "size", 1, 65536));
        scene.options.emplace_back(scene_flag::size, std::to_string(wh[0]) + "x" + std::to_string(wh[1]));
        scene.width = wh[0];
        scene.height = wh[1];
    }
    if (const YAML::Node camera = node["camera"]) {
        yaml::requireMap(camera, source_, "camera");
        yaml::requireKeys(camera, source_, kCameraKeys);
        for (const auto& [key, flag] :
             {std::pair{"eye", scene_flag::eye}, {"target", scene_flag::target}, {"up", scene_flag::up}})
            if (camera[key]) scene.options.emplace_back(flag, vec3(camera[key], key));
        if (const YAML::Node fov = camera["fov"]) {
            const std::string f = number(fov, "fov");
            if (double x = fov.as<double>(); !(x > 0 && x < 180)) throw Error(at(fov) + ": fov must be in (0, 180) degrees");
            scene.options.emplace_back(scene_flag::fov, f);
        }
        if (const YAML::Node zoom = camera["zoom"]) {
            const std::string z = number(zoom, "zoom");
            if (!(zoom.as<double>() >= 1)) throw Error(at(zoom) + ": zoom must be a factor >= 1");
            scene.options.emplace_back(scene_flag::zoom, z);
        }
        if (const YAML::Node centre = camera["zoom_centre"]) {
            if (!centre.IsSequence() || centre.size() != 2)
                throw Error(at(centre) + ": zoom_centre must be [x, y], pixels of the full frame");
            scene.options.emplace_back(scene_flag::zoomCentre,
                                       number(centre[0], "zoom_centre") + "," + number(centre[1], "zoom_centre"));
        }
    }
    if (const YAML::Node png = node["png"]) {
        yaml::requireMap(png, source_, "png");
        yaml::requireKeys(png, source_, kPngKeys);
        if (png["invert"] && flag(png["invert"], "png.invert")) scene.options.emplace_back(scene_flag::pngInvert, "");
        if (const YAML::Node e = png["exposure"]) {
            parsePositive(number(e, "png.exposure"), at(e) + ": png.exposure");
            scene.options.emplace_back(scene_flag::pngExposure, e.Scalar());
        }
        if (png["background"])
            scene.options.emplace_back(scene_flag::background, vec3(png["background"], "png.background"));
    }
    return scene;
}

void ExperimentReader::readRenderers(const YAML::Node& node) {
    for (const auto& [name, entry] : entries(node, "renderers")) {
        yaml::requireKeys(entry, source_, kRendererKeys);
        const YAML::Node command = required(entry, "command", "renderer '" + name + "'");
        if (!command.IsSequence() || command.size() == 0)
            throw Error(at(command) + ": command must be a list of words, the program first");
        Renderer renderer;
        for (const YAML::Node& word : command) renderer.command.push_back(text(word, "command"));
        renderer.image = entry["image"] ? text(entry["image"], "image") : "exr";
        if (const YAML::Node t = entry["timeout"]) {  // seconds a run may take: vri-outside's --timeout
            renderer.timeout = number(t, "timeout");
            if (!(t.as<double>() > 0.0)) throw Error(at(t) + ": timeout must be seconds > 0, got " + renderer.timeout);
        }
        if (renderer.image != "exr" && renderer.image != "png" && renderer.image != "f32")
            throw Error(at(entry["image"]) + ": image must be exr, png or f32, got '" + printable(renderer.image) + "'");
        try {  // the placeholders checked now, not when the step runs; {vri_bin} is known now: vri-run's folder
            expandPlaceholders(renderer.command, {{"card", ""}, {"voxels", ""}, {"output", ""}, {"stats", ""},
                                                  {"step", ""}, {"seed", ""}, {"width", ""}, {"height", ""}, {"vri_bin", ""}});
            const std::string tools = thisProgramFolder().string();
            for (std::string& word : renderer.command)
                for (std::size_t at = word.find("{vri_bin}"); at != std::string::npos; at = word.find("{vri_bin}", at))
                    word.replace(at, 9, tools);
        } catch (const Error& e) {
            throw Error(at(command) + ": " + e.what());
        }
        // A word that names a file beside the experiment (a script, a model) is made absolute, so that the
        // command runs from any folder, and its digest joins the executable's in the run's cache key.
        for (std::size_t i = 0; i < renderer.command.size(); ++i) {
            std::string& word = renderer.command[i];
            // The program's bare name is looked up in PATH (below), as execvp would; any other word may name a file.
            if (word.empty() || word.find('{') != std::string::npos || (i == 0 && word.find('/') == std::string::npos))
                continue;
            const fs::path path = fs::path(word).is_absolute() ? fs::path(word) : baseDir_ / word;
            if (fs::is_regular_file(path)) {
                word = fs::absolute(path).lexically_normal().string();
                renderer.files.push_back(word);
            }
        }
        const std::optional<fs::path> program = findProgram(renderer.command[0]);
        if (!program)
            throw Error(at(command[0]) + ": renderer '" + name + "': no program '" + printable(renderer.command[0]) +
                        "' (in PATH, or a path from the experiment's folder)");
        renderer.files.insert(renderer.files.begin(), fs::absolute(*program));
        renderers_.emplace(name, std::move(renderer));
    }
}

void ExperimentReader::readRuns(const YAML::Node& node, bool reference, Experiment& experiment) const {
    const char* section = reference ? "references" : "methods";
    for (const auto& [prefix, entry] : entries(node, section)) {
        // The parameters, each a list of values (a scalar is a list of one that does not show in ids).
        struct Axis {
            const RenderOptionRow* row;
            std::vector<std::string> values;
            bool swept;
        };
        std::vector<Axis> axes;
        std::vector<std::string> scenes;
        bool hasMethod = false;
        int tiles = 1;
        std::string tilesAt;  // file:line:col of `tiles:`
        glm::ivec3 bricks{1, 1, 1};
        std::string bricksAt;                // file:line:col of `bricks:`
        const Renderer* renderer = nullptr;  // `renderer: NAME`: an outside renderer's run (vri-outside)
        std::string rendererName;
        for (const auto& kv : entry) {
            const std::string key = text(kv.first, "key");
            if (key == "renderer") {
                const std::string name = text(kv.second, "renderer");
                const auto found = renderers_.find(name);
                if (found == renderers_.end())
                    throw Error(at(kv.second) + ": unknown renderer '" + printable(name) + "' (renderers: names them)");
                if (reference) throw Error(at(kv.first) + ": a reference is vri's own: renderer: belongs under methods");
                renderer = &found->second;
                rendererName = name;
                continue;
            }
            if (key == "tiles") {  // how the run is computed, not what: one value, never in the id
                tilesAt = at(kv.second);
                tiles = static_cast<int>(yaml::toWholeNumber(kv.second, source_, "tiles", 1, kMaxTiles));
                continue;
            }
            if (key == "bricks") {  // how the run is computed, not what: never in the id
                bricksAt = at(kv.second);
                if (!kv.second.IsSequence() || kv.second.size() != 3)
                    throw Error(at(kv.second) + ": bricks must be a list of three whole numbers [NX, NY, NZ]");
                for (std::size_t a = 0; a < 3; ++a)
                    bricks[static_cast<int>(a)] = static_cast<int>(
                        yaml::toWholeNumber(kv.second[a], source_, "bricks", 1, BrickGrid::kMaxPerAxis));
                continue;
            }
            if (key == "scenes") {
                scenes = names(kv.second, "scenes");
                for (std::size_t i = 0; i < scenes.size(); ++i)
                    if (std::none_of(experiment.scenes.begin(), experiment.scenes.end(),
                                     [&](const SceneSpec& s) { return s.name == scenes[i]; }))
                        throw Error(at(kv.second) + ": unknown scene '" + scenes[i] + "'");
                continue;
            }
            const RenderOptionRow* row = findRenderOption(key);
            if (!row) {
                std::string list;
                for (const std::string_view k : kMethodKeysBesideOptions) list += (list.empty() ? "" : ", ") + std::string(k);
                for (const RenderOptionRow& r : renderOptionTable())
                    if (!r.key.empty()) list += ", " + std::string(r.key);
                throw Error(at(kv.first) + ": unknown key '" + key + "' (expected one of: " + list + ")");
            }
            hasMethod = hasMethod || key == "method";
            Axis axis{row, {}, kv.second.IsSequence()};
            if (axis.swept && kv.second.size() == 0) throw Error(at(kv.second) + ": " + key + ": an empty list");
            const auto value = [&](const YAML::Node& v) {
                if (!v.IsScalar()) throw Error(at(v) + ": " + key + " must be a value or a list of values");
                if (auto values = row->hostValues ? row->hostValues(v.Scalar()) : std::nullopt) {
                    // A value that stands for this host's list (simd: lower): swept.
                    if (values->empty())
                        throw Error(at(v) + ": " + key + ": '" + v.Scalar() + "' stands for no value on this host");
                    for (std::string& each : *values) axis.values.push_back(std::move(each));
                    axis.swept = true;
                    return;
                }
                RenderRequest scratch(RenderTool::Render);  // the row's own check, where the value is
                row->apply(v.Scalar(), at(v) + ": " + key, scratch);
                axis.values.push_back(v.Scalar());
            };
            if (axis.swept)
                for (const YAML::Node& v : kv.second) value(v);
            else
                value(kv.second);
            axes.push_back(std::move(axis));
        }
        if (!hasMethod) {  // the entry's name is the method, as in `riemann: {step: [...]}`
            static const RenderOptionRow* method = findRenderOption("method");
            // An outside renderer's card describes vri's Riemann sum unless the entry names another method.
            const std::string name = renderer ? "riemann" : prefix;
            RenderRequest scratch(RenderTool::Render);
            method->apply(name, at(entry) + ": " + section + " entry '" + prefix + "' has no method, and its name",
                          scratch);
            axes.insert(axes.begin(), Axis{method, {name}, false});
        }
        if (scenes.empty())
            for (const SceneSpec& s : experiment.scenes) scenes.push_back(s.name);

        // Counted before expanding: the product of the lists' lengths, saturating, and the runs before it.
        std::uint64_t runs = scenes.size();
        for (const Axis& axis : axes) runs = checkedProduct({runs, axis.values.size()}).value_or(UINT64_MAX);
        const std::size_t before = experiment.runs.size();
        runs = runs > kMaxRuns ? runs : runs + before;
        if (runs > kMaxRuns)
            throw Error(at(entry) + ": " + section + " entry '" + prefix + "'" +
                        (before > 0 ? " with the " + std::to_string(before) + " runs before it" : "") + ": needs " +
                        (runs == UINT64_MAX ? "more than 2^64" : std::to_string(runs)) + " runs, limit " +
                        std::to_string(kMaxRuns));
        // The cartesian product, the last axis varying fastest (as nested loops in file order).
        std::vector<std::size_t> index(axes.size(), 0);
        for (const std::string& scene : scenes) {
            for (bool more = true; more;) {
                RunSpec run{experiment.scenes.size() > 1 ? scene + "-" + prefix : prefix, "vri-render", scene, reference, {}, {}, 1, {}, {}, {}, {}, {}};
                const auto method = std::find_if(axes.begin(), axes.end(), [](auto& a) { return a.row->key == "method"; });
                const std::string& methodName = method->values[index[method - axes.begin()]];
                const bool exact = methodName == kExactMethod;
                if (exact) run.tool = "vri-reference";
                if (renderer) {
                    if (exact)
                        throw Error(at(entry) + ": renderer: runs another renderer on a card of vri's own methods, not " +
                                    methodName);
                    run.tool = "vri-outside";
                    run.command = renderer->command;
                    run.rendererName = rendererName;
                    run.rendererTimeout = renderer->timeout;
                    run.rendererImage = renderer->image;
                    run.commandFiles = renderer->files;
                }
                RenderRequest request(exact ? RenderTool::Reference : RenderTool::Render);
                for (std::size_t a = 0; a < axes.size(); ++a) {
                    const RenderOptionRow& row = *axes[a].row;
                    const std::string& v = axes[a].values[index[a]];
                    if (!row.takenBy(request.tool))
                        throw Error(at(entry) + ": " + std::string(row.key) +
                                    " does not apply to method exact (vri-reference)");
                    row.apply(v, std::string(row.key), request);
                    request.given.push_back(row.flag());
                    run.parameters.emplace_back(row.key, v);
                    if (row.kind != OptionValueKind::Flag) run.options.emplace_back(row.flag(), v);
                    else if (v == "true") run.options.emplace_back(row.flag(), "");  // a flag has no value
                    // The exact method's eps is a quadrature tolerance per TF piece, no bound on the error:
                    // its id says "tol" (exact-quadrature-tol1e-7), not eps, which reads as an error level.
                    const std::string_view idPrefix = exact && row.key == "eps" ? "tol" : row.idPrefix;
                    if (axes[a].swept) run.id.append("-").append(idPrefix).append(v);
                }
                try {  // the rules between the options, as the tool will check them
                    finishRenderRequest(request);
                } catch (const Error& e) {
                    throw Error(at(entry) + ": " + section + " entry '" + prefix + "': " + e.what());
                }
                if (tiles > 1) {
                    const std::string tiled = tilesAt + ": tiles: " + std::to_string(tiles) + ": ";
                    if (renderer)
                        throw Error(tiled + "method " + methodName + " (" + run.tool + ") renders whole images only");
                    if (request.options.logPixel) throw Error(tiled + "log_ray logs one pixel: render it untiled");
                    // Each tile's --max-error search would see its own pixels only and find its own tolerance:
                    // the bands would not join into the untiled image (vri-merge-tiles refuses them).
                    if (request.maxError)
                        throw Error(tiled + "max_error searches a tolerance over the whole image; each tile would find "
                                            "its own: give the tolerance (eps) that an untiled max_error run records, "
                                            "or render untiled");
                    if (const int rows = experiment.scene(scene).height; tiles > rows)
                        throw Error(tiled + "more tiles than the " + std::to_string(rows) + " rows of scene '" + scene +
                                    "' (a tile is a band of whole rows)");
                }
                if (bricks != glm::ivec3(1)) {
                    const std::string bricked = bricksAt + ": bricks: ";
                    if (renderer || exact)
                        throw Error(bricked + "method " + methodName + " (" + run.tool +
                                    ") renders whole volumes only");
                    if (request.clamp) throw Error(bricked + "clamp clamps the joined image, not a brick's layer");
                    const SceneSpec& s = experiment.scene(scene);
                    if (std::none_of(s.options.begin(), s.options.end(),
                                     [](auto& o) { return o.first == scene_flag::volume; }))
                        throw Error(bricked + "scene '" + scene + "' is an analytic field, not a volume to cut");
                    try {
                        requireBrickable(request.options);
                    } catch (const Error& e) {
                        throw Error(bricked + e.what());
                    }
                }
                run.tiles = tiles;
                run.bricks = bricks;
                if (!isSafeName(run.id))  // a swept value is part of the id
                    throw Error(at(entry) + ": " + section + " entry '" + prefix +
                                "': a swept value does not fit in a run id (" + std::string(kSafeName) + ")");
                if (std::any_of(experiment.runs.begin(), experiment.runs.end(), [&](auto& r) { return r.id == run.id; }))
                    throw Error(at(entry) + ": run id '" + run.id + "' is used twice (rename one of the entries)");
                experiment.runs.push_back(std::move(run));
                more = false;
                for (std::size_t a = axes.size(); a-- > 0 && !more;) {
                    more = ++index[a] < axes[a].values.size();
                    if (!more) index[a] = 0;
                }
            }
        }
    }
}

void ExperimentReader::readComparisons(const YAML::Node& node, Experiment& experiment) const {
    for (const auto& [group, entry] : entries(node, "comparisons")) {
        yaml::requireKeys(entry, source_, kComparisonKeys);
        const YAML::Node ref = required(entry, "reference", "comparison '" + group + "'");
        const std::string reference = text(ref, "reference");
        requireRun(experiment, reference, ref);
        std::vector<std::string> runs;
        if (const YAML::Node r = entry["runs"]) {
            runs = names(r, "runs");
            for (const std::string& id : runs) requireRun(experiment, id, r);
        } else {  // every other method run of the reference's scene
            for (const RunSpec& r : experiment.runs)
                if (!r.reference && r.id != reference && r.scene == experiment.run(reference).scene) runs.push_back(r.id);
        }
        ComparisonSpec base{"", group, reference, "", {"0.01", "0.005", "0.001"}, "", "", false, false, "", "", "", false};
        if (const YAML::Node t = entry["thresholds"]) {
            if (!t.IsSequence() || t.size() == 0) throw Error(at(t) + ": thresholds must be a list of numbers");
            base.thresholds.clear();
            for (const YAML::Node& v : t) {
                parseNonNegative(number(v, "thresholds"), at(v) + ": thresholds");
                base.thresholds.push_back(v.Scalar());
            }
        }
        if (const YAML::Node d = entry["diff_image"]) {
            base.diffImage = text(d, "diff_image");
            if (base.diffImage == "none") base.diffImage.clear();
            else if (base.diffImage != "png" && base.diffImage != "exr")
                throw Error(at(d) + ": diff_image must be png, exr or none, got '" + base.diffImage + "'");
        }
        if (const YAML::Node k = entry["diff_scale"]) {
            if (base.diffImage.empty()) throw Error(at(k) + ": diff_scale needs diff_image");
            if (k.IsScalar() && k.Scalar() == "shared") {
                if (base.diffImage != "png") throw Error(at(k) + ": diff_scale: shared is the scale of PNG heat maps (diff_image: png)");
                base.sharedScale = true;
            } else {
                base.diffScale = number(k, "diff_scale");
                parsePositive(base.diffScale, at(k) + ": diff_scale");
            }
        }
        if (entry["histogram"]) base.histogram = flag(entry["histogram"], "histogram");
        if (const YAML::Node h = entry["heat_scale"]) {
            base.heatScale = text(h, "heat_scale");
            const std::optional<int> decades = heatScaleDecades(base.heatScale);
            if (!decades)
                throw Error(at(h) + ": heat_scale must be linear, log or log:N (N decades in 1..12), got '" +
                            printable(base.heatScale) + "'");
            if (base.diffImage != "png") throw Error(at(h) + ": heat_scale is the colour scale of PNG heat maps (diff_image: png)");
            if (*decades == 0) base.heatScale.clear();  // linear: vri-diff's default
        }
        if (const YAML::Node t = entry["heat_top"]) {
            base.heatTop = text(t, "heat_top");
            if (!heatTopPercentile(base.heatTop))
                throw Error(at(t) + ": heat_top must be max or pN (N in (0, 100]), got '" + printable(base.heatTop) + "'");
            if (base.diffImage != "png") throw Error(at(t) + ": heat_top is the top of PNG heat maps (diff_image: png)");
            if (!base.diffScale.empty()) throw Error(at(t) + ": heat_top and a numeric diff_scale both set the top");
            if (base.heatTop == "max") base.heatTop.clear();  // vri-diff's default
        }
        if (const YAML::Node g = entry["heat_signed"]) {
            base.heatSigned = flag(g, "heat_signed");
            if (base.heatSigned && base.diffImage != "png")
                throw Error(at(g) + ": heat_signed draws PNG heat maps (diff_image: png)");
            if (base.heatSigned && !base.heatScale.empty())
                throw Error(at(g) + ": heat_signed maps are linear; drop heat_scale");
        }
        if (const YAML::Node m = entry["mask"]) {
            base.mask = text(m, "mask");
            try {
                if (parseMaskSpec(base.mask).kind == MaskSpec::Kind::Image) {
                    const fs::path image = baseDir_ / base.mask;
                    if (!fs::is_regular_file(image))
                        throw Error("no mask image " + image.string() + " (all, hit, alpha>T, or an image's path)");
                    base.mask = fs::absolute(image).lexically_normal().string();
                }
            } catch (const Error& e) {
                throw Error(at(m) + ": mask: " + e.what());
            }
        }
        for (const std::string& run : runs) {
            ComparisonSpec c = base;
            c.id = comparisonId(group, run, experiment.run(run).scene);
            const auto sameId = [&](const auto& other) { return other.id == c.id; };
            if (std::ranges::any_of(experiment.runs, sameId) || std::ranges::any_of(experiment.comparisons, sameId))
                throw Error(at(entry) + ": comparison '" + group + "' of run '" + run + "' has the id '" + c.id +
                            "', which another run or comparison has (rename the comparison)");
            c.run = run;
            experiment.comparisons.push_back(std::move(c));
        }
    }
}

void ExperimentReader::readCommands(const YAML::Node& node, Experiment& experiment) const {
    for (const auto& [name, entry] : entries(node, "commands")) {
        yaml::requireKeys(entry, source_, kCommandKeys);
        const std::string what = "command '" + name + "'";
        const YAML::Node tool = required(entry, "tool", what);
        CommandSpec command{name, text(tool, "tool"), {}, {}, {}, {}, {}, {}, {}, {}, {}};
        if (!command.tool.starts_with("vri-") || command.tool.size() == 4 ||
            command.tool.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-", 4) != std::string::npos)
            throw Error(at(tool) + ": tool must be a vri tool (vri-[a-z0-9-]+), got '" + command.tool + "'");
        if (command.tool == "vri-run" || command.tool == "vri-data")  // they write outside the results folder
            throw Error(at(tool) + ": " + command.tool + " cannot be a command's tool");
        if (const YAML::Node r = entry["renderer"]) {
            const std::string rendererName = text(r, "renderer");
            const auto found = renderers_.find(rendererName);
            if (found == renderers_.end())
                throw Error(at(r) + ": unknown renderer '" + printable(rendererName) + "' (renderers: names them)");
            if (command.tool != "vri-verify" && command.tool != "vri-outside")
                throw Error(at(r) + ": renderer: applies to vri-verify and vri-outside, not " + command.tool);
            command.command = found->second.command;
            command.rendererName = rendererName;
            command.rendererTimeout = found->second.timeout;
            const YAML::Node scene = required(entry, "scene", what + " with a renderer");
            command.scene = text(scene, "scene");
            if (std::none_of(experiment.scenes.begin(), experiment.scenes.end(),
                             [&](const SceneSpec& sc) { return sc.name == command.scene; }))
                throw Error(at(scene) + ": unknown scene '" + printable(command.scene) + "'");
            command.rendererImage = found->second.image;
            const SceneSpec& sceneSpec = experiment.scene(command.scene);
            command.pixels = static_cast<std::uint64_t>(sceneSpec.width) * static_cast<std::uint64_t>(sceneSpec.height);
            command.commandFiles = found->second.files;
        }
        if (entry["scene"] && command.scene.empty())
            throw Error(at(entry["scene"]) + ": scene: goes with renderer: (vri-verify, vri-outside)");
        if (const YAML::Node options = entry["options"])
            for (const auto& [key, value] : optionEntries(options, "options"))
                if (const auto v = optionValue(value, key)) {
                    if (!v->empty() && kOutputOptions.contains(optionWord(key)))
                        throw Error(at(value) + ": option '" + key + "' writes a file: name it under outputs:");
                    if (namesFile(*v))
                        throw Error(at(value) + ": option '" + key +
                                    "' names a file or an option: files go under inputs: or outputs:");
                    command.options.emplace_back(optionWord(key), *v);
                    // What its Slurm job asks for (slurm_jobs.h), read here, where an error can name the line.
                    if (key == "threads") command.threads = parseCount(*v, at(value) + ": threads", 0);
                    if (key == "size") {
                        const glm::ivec2 size = parseSize(*v, at(value) + ": size");
                        command.pixels = static_cast<std::uint64_t>(size.x) * static_cast<std::uint64_t>(size.y);
                    }
                }
        if (const YAML::Node inputs = entry["inputs"])
            for (const auto& [key, value] : optionEntries(inputs, "inputs")) {
                if (kOutputOptions.contains(optionWord(key)))
                    throw Error(at(value) + ": input '" + key +
                                "' is an option that writes a file: name it under outputs:");
                command.inputs.emplace_back(optionWord(key), existingFile(value, "input '" + key + "'"));
            }
        const YAML::Node outputs = required(entry, "outputs", what);
        for (const auto& [key, value] : optionEntries(outputs, "outputs"))
            command.outputs.emplace_back(optionWord(key), resultFile(value, key));
        if (command.outputs.empty()) throw Error(at(outputs) + ": " + what + " has no outputs");
        experiment.commands.push_back(std::move(command));
    }
}

void ExperimentReader::readTables(const YAML::Node& node, Experiment& experiment) const {
    for (const auto& [name, entry] : entries(node, "tables")) {
        yaml::requireKeys(entry, source_, kTableKeys);
        TableSpec table;
        table.name = table.title = name;
        if (entry["value"]) {
            table.value = text(entry["value"], "value");
            requireStatsField(table.value, at(entry["value"]) + ": value");
        }
        if (entry["column"]) table.column = text(entry["column"], "column");
        if (entry["title"]) table.title = text(entry["title"], "title");
        if (const YAML::Node p = entry["precision"]) {
            table.precision = text(p, "precision");
            if (const double d = yaml::toDouble(p, source_, "precision"); d != std::floor(d) || d < 0 || d > 17)
                throw Error(at(p) + ": precision must be a whole number of decimals in 0..17");
        }
        if (const YAML::Node c = entry["comparisons"]) {
            table.comparisons = names(c, "comparisons");
            for (const std::string& group : table.comparisons)
                if (std::none_of(experiment.comparisons.begin(), experiment.comparisons.end(),
                                 [&](auto& x) { return x.group == group; }))
                    throw Error(at(c) + ": unknown comparison '" + group + "'");
        }
        if (const YAML::Node r = entry["runs"]) {
            table.runs = names(r, "runs");
            for (const std::string& id : table.runs) requireRun(experiment, id, r);
        }
        if (const YAML::Node g = entry["group_by"]) {
            if (text(g, "group_by") != "scene") throw Error(at(g) + ": group_by must be scene");
            if (!table.comparisons.empty()) throw Error(at(g) + ": group_by applies to a table of values (runs)");
            table.byScene = true;
            if (table.runs.empty())  // every method run
                for (const RunSpec& run : experiment.runs)
                    if (!run.reference) table.runs.push_back(run.id);
        }
        if (const YAML::Node l = entry["layout"]) {
            table.layout = text(l, "layout");
            if (table.layout != "thresholds" && table.layout != "matrix" && table.layout != "tradeoff" &&
                table.layout != "convergence")
                throw Error(at(l) + ": layout must be thresholds, matrix, tradeoff or convergence, got '" +
                            table.layout + "'");
            const bool matrix = table.layout == "matrix";
            if (table.comparisons.empty() != matrix || table.runs.empty() == matrix)
                throw Error(at(l) + ": layout " + table.layout +
                            (matrix ? " takes runs, not comparisons" : " takes comparisons, not runs"));
        } else {
            if (table.comparisons.empty() == table.runs.empty())
                throw Error(at(entry) + ": table '" + name + "' needs either comparisons (a threshold table) or runs (a table of values)");
            table.layout = table.comparisons.empty() ? "matrix" : "thresholds";
        }
        for (const char* key : {"value", "column"})
            if (entry[key] && table.layout != "matrix")
                throw Error(at(entry[key]) + ": " + key + " applies to a table of values (runs)");
        for (const char* key : {"threshold", "baseline", "channels"})
            if (entry[key] && table.layout != "tradeoff") throw Error(at(entry[key]) + ": " + key + " applies to layout tradeoff");
        if (const YAML::Node t = entry["threshold"]) {  // a value or a list of them
            table.thresholds.clear();
            for (const YAML::Node& v : t.IsSequence() ? std::vector<YAML::Node>(t.begin(), t.end()) : std::vector{t}) {
                table.thresholds.push_back(number(v, "threshold"));
                parseNonNegative(table.thresholds.back(), at(v) + ": threshold");
            }
            if (table.thresholds.empty()) throw Error(at(t) + ": threshold: an empty list");
        }
        if (const YAML::Node b = entry["baseline"]) {
            table.baseline = text(b, "baseline");
            if (std::none_of(experiment.comparisons.begin(), experiment.comparisons.end(), [&](auto& c) {
                    return c.run == table.baseline && std::ranges::count(table.comparisons, c.group) > 0;
                }))
                throw Error(at(b) + ": baseline '" + table.baseline + "' is not a run of the table's comparisons");
        }
        if (const YAML::Node c = entry["channels"]) {
            table.channels = text(c, "channels");
            if (table.channels != "all" && table.channels != "worst")
                throw Error(at(c) + ": channels must be all or worst, got '" + table.channels + "'");
        }
        if (const YAML::Node r = entry["rows"]) {
            if (table.layout != "thresholds") throw Error(at(r) + ": rows applies to layout thresholds");
            for (const auto& kv : r) {
                std::pair<std::string, std::vector<std::string>> row{text(kv.first, "row label"), names(kv.second, "row runs")};
                for (const std::string& run : row.second) {
                    const auto compared = std::count_if(experiment.comparisons.begin(), experiment.comparisons.end(), [&](auto& c) {
                        return c.run == run && std::ranges::count(table.comparisons, c.group) > 0;
                    });
                    if (compared != 1)
                        throw Error(at(kv.second) + ": row '" + row.first + "': run '" + run + "' is compared " +
                                    std::to_string(compared) + " times in the table's comparisons (expected once)");
                }
                const std::size_t thresholds = std::find_if(experiment.comparisons.begin(), experiment.comparisons.end(), [&](auto& c) {
                    return c.run == row.second.front() && std::ranges::count(table.comparisons, c.group) > 0;
                })->thresholds.size();
                if (row.second.size() != 1 && row.second.size() != thresholds)
                    throw Error(at(kv.second) + ": row '" + row.first + "' needs one run, or one per threshold (" +
                                std::to_string(thresholds) + "), got " + std::to_string(row.second.size()));
                table.rows.push_back(std::move(row));
            }
        }
        if (table.layout == "tradeoff")  // vri-diff counts only the thresholds it is given
            for (const std::string& group : table.comparisons) {
                const auto& thresholds = std::find_if(experiment.comparisons.begin(), experiment.comparisons.end(),
                                                      [&](auto& x) { return x.group == group; })->thresholds;
                std::string counted;
                for (const std::string& t : thresholds) counted += (counted.empty() ? "" : ", ") + t;
                for (const std::string& wanted : table.thresholds)
                    if (std::none_of(thresholds.begin(), thresholds.end(),
                                     [&](const std::string& t) { return std::stod(t) == std::stod(wanted); }))
                        throw Error(at(entry["threshold"] ? entry["threshold"] : entry) + ": threshold " + wanted +
                                    " is not one that comparison '" + group + "' counts (" + counted + ")");
            }
        experiment.tables.push_back(std::move(table));
    }
}

void ExperimentReader::readFigures(const YAML::Node& node, Experiment& experiment) const {
    for (const auto& [name, entry] : entries(node, "figures")) {
        yaml::requireKeys(entry, source_, kFigureKeys);
        FigureSpec figure{name, existingFile(required(entry, "spec", "figure '" + name + "'"), "spec"), {}, {}};
        if (const YAML::Node d = entry["data"]) {  // whether some step writes each file, the plan checks
            figure.data = names(d, "data");
            figure.dataAt = at(d);
        }
        experiment.figures.push_back(std::move(figure));
    }
}

void ExperimentReader::readReproduce(const YAML::Node& node, Experiment& experiment) const {
    yaml::requireMap(node, source_, "reproduce");
    yaml::requireKeys(node, source_, kReproduceKeys);
    double tolerance = 0;
    if (node["tolerance"]) tolerance = yaml::toDouble(node["tolerance"], source_, "tolerance");
    const YAML::Node checks = required(node, "checks", "reproduce");
    if (!checks.IsSequence() || checks.size() == 0) throw Error(at(checks) + ": checks must be a non-empty list");
    for (const YAML::Node& c : checks) {
        yaml::requireMap(c, source_, "a check");
        yaml::requireKeys(c, source_, kReproduceCheckKeys);
        ReproduceCheck check{text(required(c, "of", "a check"), "of"), {}, "", tolerance};
        if (c["tolerance"]) check.tolerance = yaml::toDouble(c["tolerance"], source_, "tolerance");
        if (!(check.tolerance >= 0)) throw Error(at(c) + ": tolerance must be >= 0");
        const auto command = std::find_if(experiment.commands.begin(), experiment.commands.end(),
                                          [&](const CommandSpec& x) { return x.name == check.of; });
        if (command != experiment.commands.end()) {
            if (c["metrics"]) throw Error(at(c["metrics"]) + ": a command's check compares a file: give file, not metrics");
            check.file = text(required(c, "file", "a command's check"), "file");
            const bool written = std::any_of(command->outputs.begin(), command->outputs.end(),
                                             [&](const auto& output) { return output.second == check.file; });
            if (!written || !check.file.ends_with(".csv"))
                throw Error(at(c["file"]) + ": '" + check.file + "' is not a CSV file that command '" + check.of + "' writes");
            experiment.reproduce.push_back(std::move(check));
            continue;
        }
        if (c["file"]) throw Error(at(c["file"]) + ": file applies to a command's check only");
        check.metrics = names(required(c, "metrics", "a check"), "metrics");
        const bool isRun = std::any_of(experiment.runs.begin(), experiment.runs.end(), [&](auto& r) { return r.id == check.of; });
        const bool isComparison = std::any_of(experiment.comparisons.begin(), experiment.comparisons.end(),
                                              [&](auto& x) { return x.id == check.of; });
        if (!isRun && !isComparison)
            throw Error(at(c["of"]) + ": '" + check.of + "' is neither a run, a comparison nor a command");
        const std::set<std::string> allowed = isRun ? std::set<std::string>{"max", "mean"}
                                                    : std::set<std::string>{"max_abs", "mean_abs", "rmse"};
        for (const std::string& m : check.metrics)
            if (!allowed.contains(m))
                throw Error(at(c["metrics"]) + ": metric '" + m + "' does not apply to " + (isRun ? "a run" : "a comparison") +
                            " (expected " + (isRun ? "max, mean" : "max_abs, mean_abs, rmse") + ")");
        experiment.reproduce.push_back(std::move(check));
    }
}

// quick: overrides. Maps merge key by key; any other value replaces the one below it.
void mergeOverrides(YAML::Node base, const YAML::Node& overrides) {
    for (const auto& kv : overrides) {
        const std::string key = kv.first.Scalar();
        const YAML::Node below = static_cast<const YAML::Node&>(base)[key];
        if (below && below.IsMap() && kv.second.IsMap())
            mergeOverrides(below, kv.second);
        else
            base[key] = kv.second;
    }
}

Experiment ExperimentReader::read(YAML::Node root, bool quick) {
    yaml::requireMap(root, source_, "an experiment");
        yaml::requireKeys(root, source_, kTopLevelKeys);
    if (const YAML::Node q = root["quick"]) {
        yaml::requireMap(q, source_, "quick");
        yaml::requireKeys(q, source_, kQuickKeys);
        if (quick) mergeOverrides(root, q);
    }
    requireAllKeys(root);
    Experiment experiment;
    experiment.source = source_;
    experiment.quick = quick;
    const YAML::Node name = required(root, "name", "the experiment");
    experiment.name = text(name, "name");
    if (!isSafeName(experiment.name))  // the experiment's folder in the results root
        throw Error(at(name) + ": name must be " + std::string(kSafeName));
    if (root["title"]) {
        experiment.title = text(root["title"], "title");
    } else {
        experiment.title = fs::path(source_).stem().string();
        defaults_.push_back("title: the file name '" + experiment.title + "'");
    }
    if (root["paper"]) experiment.paper = readPaper(root["paper"]);
    else defaults_.push_back("paper: none (an own study)");
    if (root["agreement"]) experiment.agreement = text(root["agreement"], "agreement");
    if (root["renderers"]) readRenderers(root["renderers"]);
    // Renders need scenes and methods; an experiment of commands alone (a 2D study) has neither.
    if (root["scenes"] || root["methods"] || root["references"] || !root["commands"]) {
        for (const auto& [sceneName, entry] : entries(required(root, "scenes", "the experiment"), "scenes"))
            experiment.scenes.push_back(readScene(sceneName, entry));
        if (experiment.scenes.empty()) throw Error(at(root["scenes"]) + ": no scenes");
        if (root["references"]) readRuns(root["references"], true, experiment);
        readRuns(required(root, "methods", "the experiment"), false, experiment);
    }
    if (root["comparisons"]) readComparisons(root["comparisons"], experiment);
    if (root["commands"]) readCommands(root["commands"], experiment);
    if (root["tables"]) readTables(root["tables"], experiment);
    applyTimingDefaults(experiment);
    if (root["figures"]) readFigures(root["figures"], experiment);
    if (root["reproduce"]) readReproduce(root["reproduce"], experiment);
    // Which step writes which file only the plan knows; planning once here (where to does not matter)
    // makes a figure that reads a file no step writes a mistake in the file like any other.
    planExperiment(experiment, fs::current_path() / "results" / experiment.name, fs::current_path());
    experiment.defaults.insert(experiment.defaults.begin(), defaults_.begin(), defaults_.end());
    return experiment;
}

}  // namespace

std::string comparisonId(const std::string& name, const std::string& run, const std::string& scene) {
    const auto words = [](const std::string& text) {
        std::vector<std::string> list;
        for (std::size_t start = 0, end;; start = end + 1) {
            end = text.find('-', start);
            list.push_back(text.substr(start, end - start));
            if (end == std::string::npos) return list;
        }
    };
    const std::vector<std::string> a = words(name), b = words(run);
    // Only a run id that starts with its scene shares words, and then at least the scene's.
    const std::size_t least = run.starts_with(scene + "-") ? words(scene).size() : b.size() + 1;
    std::size_t shared = std::min(a.size() - 1, b.size());
    while (shared >= least && !std::equal(a.end() - static_cast<std::ptrdiff_t>(shared), a.end(), b.begin())) --shared;
    if (shared < least) shared = 0;
    std::string id = name;
    for (std::size_t i = shared; i < b.size(); ++i) id += "-" + b[i];
    return id;
}

bool isSafeName(std::string_view name) {
    const auto alnum = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    };
    return !name.empty() && alnum(name.front()) && name.find("..") == std::string_view::npos &&
           std::all_of(name.begin(), name.end(),
                       [&](char c) { return alnum(c) || c == '.' || c == '_' || c == '+' || c == '-'; });
}

const SceneSpec& Experiment::scene(const std::string& sceneName) const {
    for (const SceneSpec& s : scenes)
        if (s.name == sceneName) return s;
    throw Error(source.string() + ": unknown scene '" + sceneName + "'");
}

const RunSpec& Experiment::run(const std::string& id) const {
    for (const RunSpec& r : runs)
        if (r.id == id) return r;
    throw Error(source.string() + ": unknown run '" + id + "'");
}

Experiment parseExperiment(const std::string& yamlText, const std::string& source, const fs::path& baseDir, bool quick) {
    return ExperimentReader(source, baseDir).read(yaml::parse(yamlText, source), quick);
}

Experiment loadExperiment(const fs::path& path, bool quick) {
    return ExperimentReader(path.string(), path.parent_path()).read(yaml::load(path), quick);
}

}  // namespace vri
