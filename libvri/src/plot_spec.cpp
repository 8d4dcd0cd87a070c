// Reading figure specs (vri-plot), with file:line:col in every error.
#include <algorithm>
#include <cmath>

#include "plot_csv.h"
#include "vri/error.h"
#include "vri/plot.h"
#include "yaml_util.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// What a spec is read against: its name for messages and the folder its data paths start from.
struct SpecSource {
    std::string name;
    fs::path baseDir;

    std::string at(const YAML::Node& node) const { return yaml::where(name, node); }
};

constexpr const char* kKeyPlacements[] = {"top left", "top right", "bottom left", "bottom right", "outside", "off"};

bool toBool(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    try {
        if (node.IsScalar()) return node.as<bool>();
    } catch (const YAML::Exception&) {
    }
    throw Error(src.at(node) + ": " + what + " must be true or false");
}

int toPositiveInt(const YAML::Node& node, const SpecSource& src, const std::string& what, int most) {
    const double value = yaml::toDouble(node, src.name, what);
    if (value < 1 || value > most || value != std::floor(value))
        throw Error(src.at(node) + ": " + what + " must be a whole number from 1 to " + std::to_string(most));
    return static_cast<int>(value);
}

// A [first, second] pair node, checked for shape.
std::pair<YAML::Node, YAML::Node> pairOf(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    if (!node.IsSequence() || node.size() != 2) throw Error(src.at(node) + ": " + what + " must be a list of two");
    return {node[0], node[1]};
}

PlotAxis parseAxis(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    PlotAxis axis;
    if (node.IsScalar()) {  // just the label
        axis.label = node.as<std::string>();
        return axis;
    }
    yaml::requireMap(node, src.name, what);
    yaml::requireKeys(node, src.name, {"label", "log", "range"});
    if (node["label"]) axis.label = yaml::toString(node["label"], src.name, what + ".label");
    if (node["log"]) axis.log = toBool(node["log"], src, what + ".log");
    if (node["range"]) {
        const auto [lo, hi] = pairOf(node["range"], src, what + ".range");
        axis.min = yaml::toDouble(lo, src.name, what + ".range");
        axis.max = yaml::toDouble(hi, src.name, what + ".range");
        if (!(*axis.min < *axis.max)) throw Error(src.at(node["range"]) + ": " + what + ".range must be [low, high]");
        if (axis.log && *axis.min <= 0)
            throw Error(src.at(node["range"]) + ": " + what + ".range must be positive on a log axis");
    }
    return axis;
}

int columnIndex(const std::vector<std::string>& header, const std::string& name, const YAML::Node& node,
                const SpecSource& src, const fs::path& file) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it != header.end()) return static_cast<int>(it - header.begin()) + 1;
    std::string known;
    for (const std::string& column : header) known += (known.empty() ? "" : ", ") + column;
    throw Error(src.at(node) + ": column '" + name + "' is not in " + file.string() + " (it has: " + known + ")");
}

bool isHexColour(const std::string& text) {
    return text.size() == 7 && text[0] == '#' &&
           std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

PlotSeries parseSeries(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    yaml::requireMap(node, src.name, what);
    yaml::requireKeys(node, src.name, {"file", "x", "y", "style", "label", "color"});
    PlotSeries series;
    if (node["style"]) {
        series.style = yaml::toString(node["style"], src.name, what + ".style");
        if (std::none_of(std::begin(kPlotStyles), std::end(kPlotStyles), [&](const char* s) { return series.style == s; }))
            throw Error(src.at(node["style"]) + ": style '" + series.style +
                        "' is unknown (expected line, dashed, dotted, points, linespoints or histogram)");
    }
    const bool histogram = series.style == "histogram";
    for (const char* key : {"file", "y"})
        if (!node[key]) throw Error(src.at(node) + ": " + what + " is missing '" + key + "'");
    if (!histogram && !node["x"]) throw Error(src.at(node) + ": " + what + " is missing 'x'");
    if (histogram && node["x"])
        throw Error(src.at(node["x"]) + ": a histogram takes its bins from the columns bin_lo and bin_hi; no 'x'");

    const std::string file = yaml::toString(node["file"], src.name, what + ".file");
    series.file = (fs::path(file).is_absolute() ? fs::path(file) : src.baseDir / file).lexically_normal();
    if (!fs::is_regular_file(series.file))
        throw Error(src.at(node["file"]) + ": data file " + series.file.string() + " does not exist");
    const std::vector<std::string> header = plot::readCsv(series.file).header;
    series.y = yaml::toString(node["y"], src.name, what + ".y");
    series.yColumn = columnIndex(header, series.y, node["y"], src, series.file);
    if (histogram) {
        series.x = "bin_lo";
        series.xColumn = columnIndex(header, "bin_lo", node["file"], src, series.file);
        columnIndex(header, "bin_hi", node["file"], src, series.file);
    } else {
        series.x = yaml::toString(node["x"], src.name, what + ".x");
        series.xColumn = columnIndex(header, series.x, node["x"], src, series.file);
    }
    series.label = node["label"] ? yaml::toString(node["label"], src.name, what + ".label") : series.y;
    if (node["color"]) {
        series.color = yaml::toString(node["color"], src.name, what + ".color");
        if (!isHexColour(series.color)) throw Error(src.at(node["color"]) + ": color must be \"#rrggbb\"");
    }
    return series;
}

PlotPanel parsePanel(const YAML::Node& node, const SpecSource& src, const std::string& what, bool titled) {
    // Fields of a panel in a list are named "panels[i].x"; those of the only panel just "x".
    auto field = [&](const std::string& name) { return what.empty() ? name : what + "." + name; };
    PlotPanel panel;
    if (titled && node["title"]) panel.title = yaml::toString(node["title"], src.name, field("title"));
    if (node["x"]) panel.x = parseAxis(node["x"], src, field("x"));
    if (node["y"]) panel.y = parseAxis(node["y"], src, field("y"));
    if (node["key"]) {
        panel.key = yaml::toString(node["key"], src.name, field("key"));
        if (std::none_of(std::begin(kKeyPlacements), std::end(kKeyPlacements), [&](const char* k) { return panel.key == k; }))
            throw Error(src.at(node["key"]) + ": key '" + panel.key +
                        "' is unknown (expected top left, top right, bottom left, bottom right, outside or off)");
    }
    if (node["pareto"]) panel.pareto = toBool(node["pareto"], src, field("pareto"));
    const YAML::Node list = node["series"];
    if (!list || !list.IsSequence() || list.size() == 0)
        throw Error(src.at(list ? list : node) + ": " + field("series") + " must be a non-empty list");
    for (std::size_t i = 0; i < list.size(); ++i)
        panel.series.push_back(parseSeries(list[i], src, field("series[" + std::to_string(i) + "]")));
    for (const PlotSeries& series : panel.series)
        if (series.style == "histogram" && panel.y.log)
            throw Error(src.at(node["y"]) + ": " + field("y") + ": histogram boxes start at 0, so y cannot be logarithmic");
    return panel;
}

PlotSpec specFromYaml(const YAML::Node& root, const SpecSource& src) {
    yaml::requireMap(root, src.name, "a figure spec");
    PlotSpec spec;
    spec.source = src.name;
    const bool multi = static_cast<bool>(root["panels"]);
    if (multi) yaml::requireKeys(root, src.name, {"title", "size", "grid", "panels"});
    else yaml::requireKeys(root, src.name, {"title", "size", "grid", "x", "y", "key", "pareto", "series"});
    if (root["title"]) spec.title = yaml::toString(root["title"], src.name, "title");
    if (root["size"]) {
        const auto [w, h] = pairOf(root["size"], src, "size");
        spec.width = toPositiveInt(w, src, "size", 10000);
        spec.height = toPositiveInt(h, src, "size", 10000);
    }
    if (multi) {
        const YAML::Node list = root["panels"];
        if (!list.IsSequence() || list.size() == 0) throw Error(src.at(list) + ": panels must be a non-empty list");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string what = "panels[" + std::to_string(i) + "]";
            yaml::requireMap(list[i], src.name, what);
            yaml::requireKeys(list[i], src.name, {"title", "x", "y", "key", "pareto", "series"});
            spec.panels.push_back(parsePanel(list[i], src, what, true));
        }
    } else {
        spec.panels.push_back(parsePanel(root, src, "", false));
    }
    const int count = static_cast<int>(spec.panels.size());
    spec.columns = static_cast<int>(std::ceil(std::sqrt(count)));
    spec.rows = (count + spec.columns - 1) / spec.columns;
    if (root["grid"]) {
        const auto [r, c] = pairOf(root["grid"], src, "grid");
        spec.rows = toPositiveInt(r, src, "grid", 100);
        spec.columns = toPositiveInt(c, src, "grid", 100);
        if (spec.rows * spec.columns < count)
            throw Error(src.at(root["grid"]) + ": grid " + std::to_string(spec.rows) + "x" +
                        std::to_string(spec.columns) + " has no room for " + std::to_string(count) + " panels");
    }
    return spec;
}

}  // namespace

PlotSpec parsePlotSpec(const std::string& yamlText, const std::string& source, const fs::path& baseDir) {
    const SpecSource src{source, baseDir};
    return specFromYaml(yaml::parse(yamlText, source), src);
}

PlotSpec loadPlotSpec(const fs::path& spec) {
    const SpecSource src{spec.string(), spec.parent_path()};
    return specFromYaml(yaml::load(spec), src);
}

}  // namespace vri
