#pragma once
// Private to vri-plot: the rows a series keeps and a heatmap's grid, read from CSV.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace vri {
struct PlotSeries;
}

namespace vri::plot {

// Whether a cell's text is what a `where` asks for: that text, or with a trailing '*' any text that
// starts with the rest ("leaves-coupled-eps0.01-*").
bool whereMatches(const std::string& text, const std::string& wanted);

// The rows of a series' file that its `where` keeps, in file order.
std::vector<std::vector<std::string>> keptRows(const PlotSeries& series);

// A heatmap's (x, y, z) fields, as written in the file, in scan order (by y, then x): gnuplot draws
// an image only from points in that order, and the file may have them in any. Columns are 1-based.
// Throws vri::Error "FILE...: what is wrong" when a field is not a number or the points do not fill
// an evenly spaced grid of at least 2 x 2, each point once.
std::vector<std::array<std::string, 3>> gridRows(const std::filesystem::path& path, int xColumn, int yColumn,
                                                 int zColumn);

}  // namespace vri::plot
