#pragma once
// Figures drawn by gnuplot from CSV data. A YAML spec says what to draw; vri writes a gnuplot
// script that is kept beside the figure, so anyone can redraw it by hand (`gnuplot fig.gp`).
#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vri {

struct PlotAxis {
    std::string label;
    bool log = false;
    std::optional<double> min, max;  // unset: gnuplot chooses
    bool dataTics = false;  // `ticks: data`: a tic at every distinct value drawn, none elsewhere
};

// Styles: line, dashed, dotted, points, linespoints;
// histogram: the bins of vri-diff's histogram CSV (columns bin_lo, bin_hi) drawn as boxes, `y` naming
//   the count column; only bins with finite positive edges are drawn (not the zero, first and overflow bins);
// heatmap: a function over a rectangle drawn as an image, coloured by the value column `z` and keyed by
//   the panel's colour bar; the (x, y) points must fill a regular grid, each once, in any order;
// segments: a line segment per row, from (x, y) to (x2, y2).
inline constexpr const char* kPlotStyles[] = {"line",        "dashed",    "dotted",  "points",
                                              "linespoints", "histogram", "heatmap", "segments"};
inline constexpr const char* kPlotPoints[] = {"circle", "square", "cross", "triangle", "triangle-down", "diamond"};
inline constexpr const char* kPlotPalettes[] = {"viridis", "gray", "diverging"};

struct PlotSeries {
    std::filesystem::path file;  // as resolved: relative paths in the spec are from the data folder
    std::string x, y;            // column names in the CSV header
    int xColumn = 0, yColumn = 0;  // 1-based, found from the header; for histograms xColumn is bin_lo
    int zColumn = 0;                // heatmaps: the value; 0 for other styles
    int x2Column = 0, y2Column = 0;  // segments: where each segment ends; 0 for other styles
    std::string style = "line";
    std::string label;
    std::string color;             // "#rrggbb", or empty for gnuplot's cycle
    double width = 2;              // line width, of the styles that draw lines
    double pointSize = 0.8;        // of points and linespoints
    std::string point = "circle";  // one of kPlotPoints
    // Only the rows whose columns hold these texts (1-based column, text), for several series
    // drawn from one file: `where: {panel: eye, kind: covered}`. Not for histograms and heatmaps.
    std::vector<std::pair<int, std::string>> where;
    // `optional: true`: a series whose `where` may keep no row on some hosts (a SIMD target one machine has
    // and another has not) is left out of its panel and its key when it keeps none; without it the series
    // stays in the key alone and the spec records a warning (PlotSpec::warnings).
    bool optional = false;
    int labelColumn = 0;  // 1-based: the column whose text is written beside each point (`labels:`); 0 for none
};

// How a panel with a heatmap maps values to colours.
struct PlotColorbar {
    std::string label;
    std::optional<double> min, max;  // unset: the data's range
    std::string palette = "viridis";  // one of kPlotPalettes
};

// Free text on a panel, starting at (x, y) in the axes' units.
struct PlotLabel {
    double x = 0, y = 0;
    std::string text;
};

struct PlotPanel {
    std::string title;
    PlotAxis x, y;
    std::string key = "top right";  // legend: top/bottom left/right, outside (right), below, or off
    bool pareto = false;  // draw the front of the points drawn (all series, `where` applied), both minimised
    bool equalAspect = false;  // one unit as long on x as on y, so that squares look square
    // Orders k of thin grey dashed lines y = c x^k through the rightmost point drawn (log x and y only),
    // to read a series' order of convergence against.
    std::vector<double> referenceSlopes;
    PlotColorbar colorbar;     // drawn when the panel has a heatmap
    std::vector<PlotLabel> labels;
    std::vector<PlotSeries> series;

    bool hasStyle(const std::string& style) const {
        return std::any_of(series.begin(), series.end(), [&](const PlotSeries& s) { return s.style == style; });
    }
};

struct PlotSpec {
    std::string source;  // the spec file, for messages and the script's header
    std::string title;
    int width = 800, height = 600;  // pixels, of the whole figure
    int rows = 1, columns = 1;      // the panel grid, filled row by row
    std::vector<PlotPanel> panels;
    // What a valid spec may still draw wrongly, each "spec:line:col: what": a series that keeps no row.
    std::vector<std::string> warnings;
};

// Reads and validates a spec: unknown keys, wrong types, missing CSV files, columns that are not
// in a CSV's header and heatmap rows that do not fill a grid are each one vri::Error
// "spec:line:col: what is wrong". Relative data paths start at dataDir, or where it is empty at the
// spec's folder (specDir): one spec can draw the data of several results folders.
//
//   title: Paper A, Fig. 2            # optional
//   size: [1200, 900]                 # optional, pixels (default 800x600)
//   grid: [2, 2]                      # optional, rows x columns (default: as square as fits)
//   panels:                           # or, for one panel, its keys at the top level
//     - title: sampling rate 1
//       x: {label: ray, log: false, range: [0, 120]}
//       y: {label: intensity, ticks: data}  # ticks: auto (default), or data: a tic at every value drawn
//       key: top left                 # top/bottom left/right, outside (right of the plot), below, off
//       reference_slopes: [1, 2, 4]   # optional, log x and y: y ~ x^k, dashed grey, "order k"
//       pareto: false
//       aspect: equal                 # optional: one unit as long on x as on y (default: auto)
//       labels:                       # optional free text, starting at (x, y)
//         - {x: 0.5, y: 1.2, text: midpoint}
//       colorbar: {label: error, min: 0, max: 1, palette: viridis}  # heatmaps; all optional
//       series:
//         - {file: rays.csv, x: ray, y: closed_form, style: line, label: closed form, width: 1}
//         - {file: rays.csv, x: ray, y: riemann, style: points, size: 1.5, point: square}
//         - {file: f.csv, x: u, y: v, z: f, style: heatmap}
//         - {file: steps.csv, x: t0, y: row, x2: t1, y2: row, style: segments, color: "#000000"}
//         - {file: tradeoff.csv, x: seconds, y: max, style: points, labels: run, where: {"pareto max": 1}}
//         - {file: orders.csv, x: h, y: error, style: linespoints, where: {series: a}, label_from: legend}
//         - {file: speed.csv, x: seconds, y: max, style: linespoints, where: {method: exact}, label: exact,
//            label_ends: run}                                   # keyed "exact, eps1e-6 to eps1e-7"
//         - {file: speed.csv, x: seconds, y: max, style: linespoints, group_by: method, label_ends: run}
//                                  # a series per method family, each its colour and point (below)
//
// A series' `width` (line width) is for line, dashed, dotted, linespoints and segments; `size` and
// `point` (circle, square, cross, triangle, triangle-down, diamond) for points and linespoints; heatmaps take neither
// `color` nor `label`. Without `label` a series is keyed by its y column; `label: ""` leaves it
// out of the key. `where: {column: text, ...}` keeps only the rows whose columns hold those
// texts, or with a trailing '*' start with the rest (`{run: "leaves-coupled-eps0.01-*"}`; not for histograms
// and heatmaps), so one CSV can feed several series; `optional: true` drops a series whose `where` keeps no
// row (a forced SIMD target another host lacks) from its panel and key; `label_from: column`
// keys the series with that column's text in the first row it keeps (a fitted slope, say); a line joins the
// rows kept, in file order, whatever rows lie between them. `label_ends: column` adds to the key the first
// and last kept row's text in that column past the words they share ("riemann double, h0.5 to h0.1"): the
// order in which its line runs, without a label at each point. `labels: column` writes each point's text from that column beside it
// (line, dashed, dotted, points, linespoints), e.g. the run of each point of vri-tabulate's tradeoff
// table. A panel's `pareto: true` draws the Pareto front of its points, joined in order of x.
// A log axis without a range is fitted to the points drawn (plot_axes.h): a margin beyond them, labels at
// 1, 2 and 5 times the powers of ten when it spans under three decades (every digit under one), and a y axis
// draws its values <= 0 on a grey band labelled 0 below a break in the axis, its label saying so; no two tic
// labels come closer than plot::kMinTicSpacing of the axis. `reference_slopes: [k, ...]` draws y = c x^k
// through the panel's rightmost point (the highest of those at its x), each line labelled "order k" where
// it enters the panel on the left, clipped to the panel; `ticks: data` labels every distinct value drawn on
// that axis (every step h of a convergence study), points and lines only.
// Palettes: viridis (default), gray, diverging (blue, white, red).
PlotSpec loadPlotSpec(const std::filesystem::path& spec, const std::filesystem::path& dataDir = {});
PlotSpec parsePlotSpec(const std::string& yamlText, const std::string& source, const std::filesystem::path& specDir,
                       const std::filesystem::path& dataDir = {});

// The gnuplot script for a figure whose script will be `scriptPath`: data paths are written
// relative to the script's folder (the script changes into it), and it writes pngName and
// svgName there, or to its two arguments (`gnuplot -c fig.gp PNG SVG`, which gnuplot never parses).
// Every text and file name in it is quoted so that gnuplot reads it as that text and nothing else.
std::string gnuplotScript(const PlotSpec& spec, const std::filesystem::path& scriptPath, const std::string& pngName,
                          const std::string& svgName);

// Writes png (must end in .png), and beside it the .svg and the .gp script, all atomically: each
// appears only once gnuplot has succeeded and the PNG and SVG it wrote are whole (PNG signature to
// IEND chunk, SVG to its closing tag). Throws vri::Error naming the figure when gnuplot is not
// installed, fails, or leaves an incomplete image.
void drawPlot(const PlotSpec& spec, const std::filesystem::path& png);
// Writes only the .gp script beside `png` (no gnuplot needed).
void writePlotScript(const PlotSpec& spec, const std::filesystem::path& png);

}  // namespace vri
