// Log axes fitted to a panel's data, with a floor for the values a log axis cannot show.
#include "libvri/report/plot_axes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "libvri/report/plot_csv.h"
#include "libvri/util/csv.h"

namespace vri::plot {

std::vector<std::pair<double, double>> keptPoints(const PlotSeries& series) {
    std::vector<std::pair<double, double>> points;
    for (const auto& row : keptRows(series)) {
        const std::size_t xi = series.xColumn - 1, yi = series.yColumn - 1;
        if (xi >= row.size() || yi >= row.size()) continue;
        const auto x = parseNumber(row[xi]), y = parseNumber(row[yi]);
        if (x && y && std::isfinite(*x) && std::isfinite(*y)) points.emplace_back(*x, *y);
    }
    return points;
}

std::optional<LogAxisFit> fitLogAxis(const PlotAxis& axis, const std::vector<double>& values) {
    if (!axis.log || axis.min || axis.max) return std::nullopt;
    double lo = INFINITY, hi = -INFINITY;
    bool zero = false;
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        if (v <= 0) zero = true;
        else lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (!(lo <= hi)) return std::nullopt;
    // A margin of 6 % of the span at each end (at least a factor 1.15), so no marker sits on the frame.
    const double margin = std::max(1.15, std::pow(hi / lo, 0.06));
    LogAxisFit fit{lo / margin, hi * margin, std::nullopt, {}};
    if (zero) {
        // Two margins below the smallest value, so the floor does not read as one more step down.
        fit.floor = lo / (margin * margin * margin);
        fit.min = *fit.floor / margin;
    }
    if (fit.max / fit.min < 1000) {
        const std::vector<int> steps = fit.max / fit.min < 10 ? std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}
                                                              : std::vector<int>{1, 2, 5};
        const int first = static_cast<int>(std::floor(std::log10(fit.min)));
        for (int power = first; power <= first + 3; ++power)
            for (int step : steps) {
                // Read from its decimal form, so that the tic is the double gnuplot would read for "2e-3".
                char text[16];
                std::snprintf(text, sizeof text, "%de%d", step, power);
                const double tic = std::strtod(text, nullptr);
                if (tic >= lo / margin && tic <= fit.max) fit.tics.push_back(tic);  // none between the floor and the data
            }
    }
    return fit;
}

}  // namespace vri::plot
