// Reference slopes on log-log panels, cut to the panel's box.
#include "libvri/report/plot_slopes.h"

#include <algorithm>
#include <cmath>

namespace vri::plot {

std::vector<ReferenceLine> referenceLines(const std::vector<double>& orders, std::pair<double, double> anchor,
                                          double xmin, double xmax, double ymin, double ymax) {
    std::vector<ReferenceLine> lines;
    const double xa = anchor.first, ya = anchor.second;  // named values: clang 14 cannot capture structured bindings
    for (double k : orders) {
        // y = ya (x / xa)^k rises with x: it enters the box on the left or the bottom edge and leaves it on
        // the right or the top edge. In logarithms, so that a steep order does not overflow.
        const auto xAt = [&](double y) { return xa * std::exp(std::log(y / ya) / k); };
        const auto yAt = [&](double x) { return ya * std::exp(k * std::log(x / xa)); };
        const double x1 = std::max(xmin, xAt(ymin)), x2 = std::min(xmax, xAt(ymax));
        if (x1 < x2) lines.push_back({k, x1, std::max(ymin, yAt(x1)), x2, std::min(ymax, yAt(x2))});
    }
    return lines;
}

}  // namespace vri::plot
