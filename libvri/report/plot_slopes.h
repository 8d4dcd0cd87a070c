#pragma once
// Private to vri-plot: reference lines y = c x^k on a panel with log x and y axes (`reference_slopes`),
// against which a series' order of convergence reads off as parallel or not.
#include <utility>
#include <vector>

namespace vri::plot {

// From (x1, y1), its left end, to (x2, y2).
struct ReferenceLine {
    double order = 0;
    double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};

// A line of each (positive) order through `anchor`, cut to the box [xmin, xmax] x [ymin, ymax] (gnuplot
// does not clip arrows); an order whose line misses the box has none.
std::vector<ReferenceLine> referenceLines(const std::vector<double>& orders, std::pair<double, double> anchor,
                                          double xmin, double xmax, double ymin, double ymax);

}  // namespace vri::plot
