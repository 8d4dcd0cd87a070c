#pragma once
// Figures drawn by gnuplot from CSV data. A YAML spec says what to draw; vri writes a gnuplot
// script that is kept beside the figure, so anyone can redraw it by hand (`gnuplot fig.gp`).
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
};

// Styles: line, dashed, dotted, points, linespoints, and histogram: the bins of vri-diff's
// histogram CSV (columns bin_lo, bin_hi) drawn as boxes, `y` naming the count column; only bins
// with finite positive edges are drawn (not the zero, first and overflow bins).
inline constexpr const char* kPlotStyles[] = {"line", "dashed", "dotted", "points", "linespoints", "histogram"};

struct PlotSeries {
    std::filesystem::path file;  // as resolved: relative paths in the spec are from the spec's folder
    std::string x, y;            // column names in the CSV header
    int xColumn = 0, yColumn = 0;  // 1-based, found from the header; for histograms xColumn is bin_lo
    std::string style = "line";
    std::string label;
    std::string color;  // "#rrggbb", or empty for gnuplot's cycle
};

struct PlotPanel {
    std::string title;
    PlotAxis x, y;
    std::string key = "top right";  // legend: top/bottom left/right, outside, or off
    bool pareto = false;  // mark the points of all series not dominated in (x, y), both minimised
    std::vector<PlotSeries> series;
};

struct PlotSpec {
    std::string source;  // the spec file, for messages and the script's header
    std::string title;
    int width = 800, height = 600;  // pixels, of the whole figure
    int rows = 1, columns = 1;      // the panel grid, filled row by row
    std::vector<PlotPanel> panels;
};

// Reads and validates a spec: unknown keys, wrong types, missing CSV files and columns that are
// not in a CSV's header are each one vri::Error "spec:line:col: what is wrong".
//
//   title: Paper A, Fig. 2            # optional
//   size: [1200, 900]                 # optional, pixels (default 800x600)
//   grid: [2, 2]                      # optional, rows x columns (default: as square as fits)
//   panels:                           # or, for one panel, its keys at the top level
//     - title: sampling rate 1
//       x: {label: ray, log: false, range: [0, 120]}
//       y: {label: intensity}
//       key: top left
//       pareto: false
//       series:
//         - {file: rays.csv, x: ray, y: closed_form, style: line, label: closed form}
PlotSpec loadPlotSpec(const std::filesystem::path& spec);
PlotSpec parsePlotSpec(const std::string& yamlText, const std::string& source, const std::filesystem::path& baseDir);

// Indices of the points no other point dominates (another point <= in both and < in one),
// ordered by x; of equal points only the first. Points with a non-finite coordinate are left out.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& points);

// The gnuplot script for a figure whose script will be `scriptPath`: data paths are written
// relative to the script's folder (the script changes into it), and it writes pngName and
// svgName there unless the variables png_out and svg_out are set (gnuplot -e).
std::string gnuplotScript(const PlotSpec& spec, const std::filesystem::path& scriptPath, const std::string& pngName,
                          const std::string& svgName);

// Writes png (must end in .png), and beside it the .svg and the .gp script, all atomically.
// Throws vri::Error when gnuplot is not installed or fails.
void drawPlot(const PlotSpec& spec, const std::filesystem::path& png);
// Writes only the .gp script beside `png` (no gnuplot needed).
void writePlotScript(const PlotSpec& spec, const std::filesystem::path& png);

}  // namespace vri
