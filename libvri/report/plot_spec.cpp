// Reading figure specs (vri-plot), with file:line:col in every error.
#include <algorithm>
#include <cmath>

#include "libvri/io/plot_data_files.h"
#include "libvri/io/yaml_util.h"
#include "libvri/report/plot.h"
#include "libvri/report/plot_csv.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// What a spec is read against: its name for messages and the folder its data paths start from.
struct SpecSource {
    std::string name;
    fs::path baseDir;

    std::string at(const YAML::Node& node) const { return yaml::where(name, node); }
};

constexpr const char* kKeyPlacements[] = {"top left", "top right", "bottom left", "bottom right",
                                          "outside", "below", "off"};
constexpr const char* kAspects[] = {"auto", "equal"};
constexpr const char* kTics[] = {"auto", "data"};

// Series keys that only some styles take, with those styles. A heatmap's colours and its entry in
// the legend are its panel's colour bar, so it takes no color or label.
constexpr std::pair<const char*, const char*> kStyleOnlyKeys[] = {
    {"z", "heatmap"},
    {"x2", "segments"},
    {"y2", "segments"},
    {"width", "line, dashed, dotted, linespoints, segments"},
    {"size", "points, linespoints"},
    {"point", "points, linespoints"},
    {"color", "line, dashed, dotted, points, linespoints, histogram, segments"},
    {"label", "line, dashed, dotted, points, linespoints, histogram, segments"},
    {"label_from", "line, dashed, dotted, points, linespoints, segments"},
    {"label_ends", "line, dashed, dotted, points, linespoints"},
    {"where", "line, dashed, dotted, points, linespoints, segments"},
    {"optional", "line, dashed, dotted, points, linespoints, segments"},
    {"labels", "line, dashed, dotted, points, linespoints"},
};

int toPositiveInt(const YAML::Node& node, const SpecSource& src, const std::string& what, int most) {
    const double value = yaml::toDouble(node, src.name, what);
    if (value < 1 || value > most || value != std::floor(value))
        throw Error(src.at(node) + ": " + what + " must be a whole number from 1 to " + std::to_string(most));
    return static_cast<int>(value);
}

double toPositiveNumber(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    const double value = yaml::toDouble(node, src.name, what);
    if (!(value > 0) || !std::isfinite(value)) throw Error(src.at(node) + ": " + what + " must be a positive number");
    return value;
}

// A string that must be one of `names`; the message lists them.
template <std::size_t N>
std::string toChoice(const YAML::Node& node, const SpecSource& src, const std::string& what,
                     const char* const (&names)[N]) {
    const std::string value = yaml::toString(node, src.name, what);
    if (std::any_of(std::begin(names), std::end(names), [&](const char* name) { return value == name; })) return value;
    std::string expected;
    for (std::size_t i = 0; i < N; ++i) expected += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i]);
    throw Error(src.at(node) + ": " + what + " '" + value + "' is unknown (expected " + expected + ")");
}

void requirePresent(const YAML::Node& node, const SpecSource& src, const std::string& what,
                    const std::vector<std::string>& keys) {
    for (const std::string& key : keys)
        if (!node[key]) throw Error(src.at(node) + ": " + what + " is missing '" + key + "'");
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
    yaml::requireKeys(node, src.name, {"label", "log", "range", "ticks"});
    if (node["label"]) axis.label = yaml::toString(node["label"], src.name, what + ".label");
    if (node["log"]) axis.log = yaml::toBool(node["log"], src.name, what + ".log");
    if (node["ticks"]) axis.dataTics = toChoice(node["ticks"], src, what + ".ticks", kTics) == "data";
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

// The keys the series' style needs are there, and none that it does not take.
void requireStyleKeys(const YAML::Node& node, const SpecSource& src, const std::string& what, const std::string& style) {
    for (const auto& [key, styles] : kStyleOnlyKeys)
        if (node[key] && (", " + std::string(styles) + ", ").find(", " + style + ", ") == std::string::npos)
            throw Error(src.at(node[key]) + ": " + what + "." + key + " is not for style " + style + " (only for " +
                        styles + ")");
    std::vector<std::string> required = {"file", "y"};
    if (style != "histogram") required.push_back("x");
    if (style == "heatmap") required.push_back("z");
    if (style == "segments") required.insert(required.end(), {"x2", "y2"});
    requirePresent(node, src, what, required);
    if (style == "histogram" && node["x"])
        throw Error(src.at(node["x"]) + ": a histogram takes its bins from the columns bin_lo and bin_hi; no 'x'");
}

// The columns a series names, checked against its file's header (and a heatmap's rows for their grid).
void findColumns(PlotSeries& series, const YAML::Node& node, const SpecSource& src, const std::string& what) {
    const std::vector<std::string> header = readCsv(series.file).header;
    auto column = [&](const char* key) {
        return columnIndex(header, yaml::toString(node[key], src.name, what + "." + key), node[key], src, series.file);
    };
    series.y = yaml::toString(node["y"], src.name, what + ".y");
    series.yColumn = column("y");
    if (series.style == "histogram") {
        series.x = "bin_lo";
        series.xColumn = columnIndex(header, "bin_lo", node["file"], src, series.file);
        columnIndex(header, "bin_hi", node["file"], src, series.file);
        return;
    }
    series.x = yaml::toString(node["x"], src.name, what + ".x");
    series.xColumn = column("x");
    if (node["labels"]) series.labelColumn = column("labels");
    if (series.style == "segments") {
        series.x2Column = column("x2");
        series.y2Column = column("y2");
    }
    if (const YAML::Node where = node["where"]) {
        yaml::requireMap(where, src.name, what + ".where");
        for (const auto& entry : where) {
            const std::string name = yaml::toString(entry.first, src.name, what + ".where");
            series.where.emplace_back(columnIndex(header, name, entry.first, src, series.file),
                                      yaml::toString(entry.second, src.name, what + ".where." + name));
        }
    }
    if (const YAML::Node from = node["label_from"]) {  // the key's text from the data: the first row kept
        if (node["label"]) throw Error(src.at(from) + ": " + what + " takes label or label_from, not both");
        const int index = column("label_from");
        const auto kept = plot::keptRows(series);
        if (kept.empty() || index > int(kept.front().size()))
            throw Error(src.at(from) + ": " + what + ".label_from: no row of " + series.file.string() +
                        " is kept to take the label from");
        series.label = kept.front()[index - 1];
    }
    if (series.style == "heatmap") {
        series.zColumn = column("z");
        try {
            plot::gridRows(series.file, series.xColumn, series.yColumn, series.zColumn);
        } catch (const Error& e) {
            throw Error(src.at(node["file"]) + ": " + e.what());
        }
    }
}

// ", h0.5 to h0.1": the first and last kept row's text in a column (1-based), past the words (each ended by
// '-') that they share at the start; "" when they are the same. So a key can say in which order a line
// joins a family's runs, where a label at each point would overprint its neighbours.
std::string endsText(const std::vector<std::vector<std::string>>& rows, int column) {
    const auto text = [&](const std::vector<std::string>& row) {
        return column <= int(row.size()) ? row[column - 1] : std::string();
    };
    if (rows.empty()) return "";
    const std::string first = text(rows.front()), last = text(rows.back());
    if (first == last) return "";
    std::size_t shared = 0;
    // A '-' before a digit is a number's sign (eps1e-6), not the end of a word.
    for (std::size_t i = 0; i < std::min(first.size(), last.size()) && first[i] == last[i]; ++i)
        if (first[i] == '-' && !(i + 1 < first.size() && std::isdigit(static_cast<unsigned char>(first[i + 1]))))
            shared = i + 1;
    return ", " + first.substr(shared) + " to " + last.substr(shared);
}

PlotSeries parseSeries(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    yaml::requireMap(node, src.name, what);
    yaml::requireKeys(node, src.name,
                      {"file", "x", "y", "z", "x2", "y2", "style", "label", "label_from", "color", "width", "size", "point",
                       "where", "optional", "labels", "label_ends", "group_by"});
    PlotSeries series;
    if (node["style"]) series.style = toChoice(node["style"], src, what + ".style", kPlotStyles);
    requireStyleKeys(node, src, what, series.style);

    const std::string file = yaml::toString(node["file"], src.name, what + ".file");
    series.file = plotDataPath(file, src.baseDir);
    if (!fs::is_regular_file(series.file))
        throw Error(src.at(node["file"]) + ": data file " + series.file.string() + " does not exist");
    findColumns(series, node, src, what);
    if (node["label"]) series.label = yaml::toString(node["label"], src.name, what + ".label");
    else if (!node["label_from"]) series.label = series.y;
    if (const YAML::Node ends = node["label_ends"]; ends && !node["group_by"]) {  // a group's: each member's own
        const std::string name = yaml::toString(ends, src.name, what + ".label_ends");
        const int column = columnIndex(readCsv(series.file).header, name, ends, src, series.file);
        series.label += endsText(plot::keptRows(series), column);
    }
    if (node["color"]) {
        series.color = yaml::toString(node["color"], src.name, what + ".color");
        if (!isHexColour(series.color)) throw Error(src.at(node["color"]) + ": color must be \"#rrggbb\"");
    }
    if (node["width"]) series.width = toPositiveNumber(node["width"], src, what + ".width");
    if (node["size"]) series.pointSize = toPositiveNumber(node["size"], src, what + ".size");
    if (node["point"]) series.point = toChoice(node["point"], src, what + ".point", kPlotPoints);
    if (node["optional"]) series.optional = yaml::toBool(node["optional"], src.name, what + ".optional");
    return series;
}

// Okabe and Ito's eight colours, distinct to readers with any common colour-vision deficiency, the darkest
// first (their yellow last: faint on white).
constexpr const char* kGroupColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                         "#E69F00", "#56B4E9", "#000000", "#F0E442"};

// `group_by: COLUMN`: one series per text of that column among the rows the series keeps, in the order they
// first appear, each keyed by its text (and its label_ends), in a colour of kGroupColours and a point type of
// kPlotPoints, both taken in turn, so that 48 groups differ in one or the other. A colour or point given in
// the spec holds for every group.
std::vector<PlotSeries> groupedSeries(const PlotSeries& base, const YAML::Node& node, const SpecSource& src,
                                      const std::string& what) {
    const std::vector<std::string> header = readCsv(base.file).header;
    const int column = columnIndex(header, yaml::toString(node["group_by"], src.name, what + ".group_by"),
                                   node["group_by"], src, base.file);
    const int endsColumn = node["label_ends"] ? columnIndex(header, yaml::toString(node["label_ends"], src.name,
                                                                                   what + ".label_ends"),
                                                            node["label_ends"], src, base.file)
                                              : 0;
    std::vector<std::string> groups;
    for (const std::vector<std::string>& row : plot::keptRows(base))
        if (column <= int(row.size()) && std::ranges::find(groups, row[column - 1]) == groups.end())
            groups.push_back(row[column - 1]);
    constexpr std::size_t colours = std::size(kGroupColours), points = std::size(kPlotPoints);
    std::vector<PlotSeries> out;
    for (std::size_t k = 0; k < groups.size(); ++k) {
        PlotSeries series = base;
        series.where.emplace_back(column, groups[k]);
        series.label = groups[k];
        if (endsColumn > 0) series.label += endsText(plot::keptRows(series), endsColumn);
        if (!node["color"]) series.color = kGroupColours[k % colours];
        if (!node["point"]) series.point = kPlotPoints[k % points];
        out.push_back(std::move(series));
    }
    return out;
}

PlotColorbar parseColorbar(const YAML::Node& node, const SpecSource& src, const std::string& what) {
    yaml::requireMap(node, src.name, what);
    yaml::requireKeys(node, src.name, {"label", "min", "max", "palette"});
    PlotColorbar colorbar;
    if (node["label"]) colorbar.label = yaml::toString(node["label"], src.name, what + ".label");
    if (node["min"]) colorbar.min = yaml::toDouble(node["min"], src.name, what + ".min");
    if (node["max"]) colorbar.max = yaml::toDouble(node["max"], src.name, what + ".max");
    if (colorbar.min && colorbar.max && !(*colorbar.min < *colorbar.max))
        throw Error(src.at(node["max"]) + ": " + what + ".max must be above its min");
    if (node["palette"]) colorbar.palette = toChoice(node["palette"], src, what + ".palette", kPlotPalettes);
    return colorbar;
}

// Orders of reference lines, each positive: y = c x^k rises to the right, as an error does with the step.
std::vector<double> parseSlopes(const YAML::Node& list, const SpecSource& src, const std::string& what) {
    if (!list.IsSequence() || list.size() == 0)
        throw Error(src.at(list) + ": " + what + " must be a non-empty list of orders, such as [1, 2, 4]");
    std::vector<double> orders;
    for (std::size_t i = 0; i < list.size(); ++i)
        orders.push_back(toPositiveNumber(list[i], src, what + "[" + std::to_string(i) + "]"));
    return orders;
}

std::vector<PlotLabel> parseLabels(const YAML::Node& list, const SpecSource& src, const std::string& what) {
    if (!list.IsSequence()) throw Error(src.at(list) + ": " + what + " must be a list of {x, y, text}");
    std::vector<PlotLabel> labels;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node node = list[i];
        const std::string item = what + "[" + std::to_string(i) + "]";
        yaml::requireMap(node, src.name, item);
        yaml::requireKeys(node, src.name, {"x", "y", "text"});
        requirePresent(node, src, item, {"x", "y", "text"});
        labels.push_back({yaml::toDouble(node["x"], src.name, item + ".x"),
                          yaml::toDouble(node["y"], src.name, item + ".y"),
                          yaml::toString(node["text"], src.name, item + ".text")});
    }
    return labels;
}

PlotPanel parsePanel(const YAML::Node& node, const SpecSource& src, const std::string& what, bool titled,
                     std::vector<std::string>& warnings) {
    // Fields of a panel in a list are named "panels[i].x"; those of the only panel just "x".
    auto field = [&](const std::string& name) { return what.empty() ? name : what + "." + name; };
    PlotPanel panel;
    if (titled && node["title"]) panel.title = yaml::toString(node["title"], src.name, field("title"));
    if (node["x"]) panel.x = parseAxis(node["x"], src, field("x"));
    if (node["y"]) panel.y = parseAxis(node["y"], src, field("y"));
    if (node["key"]) panel.key = toChoice(node["key"], src, field("key"), kKeyPlacements);
    if (node["pareto"]) panel.pareto = yaml::toBool(node["pareto"], src.name, field("pareto"));
    if (node["aspect"]) panel.equalAspect = toChoice(node["aspect"], src, field("aspect"), kAspects) == "equal";
    if (node["reference_slopes"])
        panel.referenceSlopes = parseSlopes(node["reference_slopes"], src, field("reference_slopes"));
    if (node["labels"]) panel.labels = parseLabels(node["labels"], src, field("labels"));
    if (node["colorbar"]) panel.colorbar = parseColorbar(node["colorbar"], src, field("colorbar"));
    const YAML::Node list = node["series"];
    if (!list || !list.IsSequence() || list.size() == 0)
        throw Error(src.at(list ? list : node) + ": " + field("series") + " must be a non-empty list");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string name = field("series[" + std::to_string(i) + "]");
        PlotSeries series = parseSeries(list[i], src, name);
        if (list[i]["group_by"] && !plot::keptRows(series).empty()) {
            if (series.style == "histogram" || series.style == "heatmap")
                throw Error(src.at(list[i]["group_by"]) + ": " + name + ".group_by: not for a " + series.style);
            for (PlotSeries& member : groupedSeries(series, list[i], src, name)) panel.series.push_back(std::move(member));
            continue;
        }
        if (plot::keptRows(series).empty()) {
            if (series.optional) continue;  // nothing of it on this host
            // Drawn as a key entry alone, which a reader may not notice: a typo in where, or a run missing.
            warnings.push_back(src.at(list[i]) + ": " + name + ": " + (series.where.empty() ? "" : "its where keeps ") +
                               "no row of " + series.file.string() +
                               ": drawn in the key alone (optional: true drops a series only some hosts or runs have)");
        }
        panel.series.push_back(std::move(series));
    }
    if (panel.series.empty())
        throw Error(src.at(list) + ": " + field("series") + ": every series is optional and keeps no row");
    if (panel.y.log && panel.hasStyle("histogram"))
        throw Error(src.at(node["y"]) + ": " + field("y") + ": histogram boxes start at 0, so y cannot be logarithmic");
    if (node["colorbar"] && !panel.hasStyle("heatmap"))
        throw Error(src.at(node["colorbar"]) + ": " + field("colorbar") + " is for panels with a heatmap series");
    if (node["reference_slopes"] && !(panel.x.log && panel.y.log))
        throw Error(src.at(node["reference_slopes"]) + ": " + field("reference_slopes") +
                    " needs log x and y axes (x: {log: true}, y: {log: true})");
    // Both come from the points that points and lines draw; histogram bins, images and segments have none.
    const bool onlyPoints = !panel.hasStyle("histogram") && !panel.hasStyle("heatmap") && !panel.hasStyle("segments");
    const auto requirePoints = [&](const YAML::Node& at, const std::string& key) {
        if (!onlyPoints)
            throw Error(src.at(at) + ": " + field(key) +
                        " is for panels of points and lines only (no histogram, heatmap or segments)");
    };
    if (node["reference_slopes"]) requirePoints(node["reference_slopes"], "reference_slopes");
    if (panel.x.dataTics) requirePoints(node["x"]["ticks"], "x.ticks");
    if (panel.y.dataTics) requirePoints(node["y"]["ticks"], "y.ticks");
    return panel;
}

PlotSpec specFromYaml(const YAML::Node& root, const SpecSource& src) {
    yaml::requireMap(root, src.name, "a figure spec");
    PlotSpec spec;
    spec.source = src.name;
    const bool multi = static_cast<bool>(root["panels"]);
    if (multi) yaml::requireKeys(root, src.name, {"title", "size", "grid", "panels"});
    else
        yaml::requireKeys(root, src.name,
                          {"title", "size", "grid", "x", "y", "key", "pareto", "aspect", "reference_slopes", "labels",
                           "colorbar", "series"});
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
            yaml::requireKeys(list[i], src.name,
                              {"title", "x", "y", "key", "pareto", "aspect", "reference_slopes", "labels", "colorbar",
                               "series"});
            spec.panels.push_back(parsePanel(list[i], src, what, true, spec.warnings));
        }
    } else {
        spec.panels.push_back(parsePanel(root, src, "", false, spec.warnings));
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

PlotSpec parsePlotSpec(const std::string& yamlText, const std::string& source, const fs::path& specDir,
                       const fs::path& dataDir) {
    const SpecSource src{source, dataDir.empty() ? specDir : dataDir};
    return specFromYaml(yaml::parse(yamlText, source), src);
}

PlotSpec loadPlotSpec(const fs::path& spec, const fs::path& dataDir) {
    const SpecSource src{spec.string(), dataDir.empty() ? spec.parent_path() : dataDir};
    return specFromYaml(yaml::load(spec), src);
}

}  // namespace vri
