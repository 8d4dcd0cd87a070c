// Log axes fitted to a panel's data, with a band below a break for the values a log axis cannot show.
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

double axisFraction(const LogAxisFit& fit, double value) {
    return std::log(value / fit.min) / std::log(fit.max / fit.min);
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
    const double bottom = lo / margin;  // of the positive values' range: the tics start here
    LogAxisFit fit{bottom, hi * margin, bottom, std::nullopt, {}};
    if (zero) {
        // The band and the break below the positive range, as fractions of the whole axis.
        const double below = kZeroBand + kZeroGap;
        const double length = std::log10(fit.max / bottom) / (1 - below);
        fit.min = bottom / std::pow(10.0, below * length);
        fit.zero = fit.min * std::pow(10.0, kZeroBand / 2 * length);
    }
    const double decades = std::log10(fit.max / bottom);
    if (decades >= 3 && !zero) return fit;  // gnuplot's decades: none falls in a band
    const std::vector<int> steps = decades >= 3  ? std::vector<int>{1}
                                   : decades < 1 ? std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}
                                                 : std::vector<int>{1, 2, 5};
    double last = fit.zero ? axisFraction(fit, *fit.zero) : -INFINITY;  // where the label below is
    const int first = static_cast<int>(std::floor(std::log10(bottom)));
    for (int power = first; power <= static_cast<int>(std::ceil(std::log10(fit.max))); ++power)
        for (int step : steps) {
            // Read from its decimal form, so that the tic is the double gnuplot would read for "2e-3".
            char text[16];
            std::snprintf(text, sizeof text, "%de%d", step, power);
            const double tic = std::strtod(text, nullptr);
            if (tic < bottom || tic > fit.max) continue;  // none in the break or the band
            if (axisFraction(fit, tic) - last < kMinTicSpacing) continue;
            fit.tics.push_back(tic);
            last = axisFraction(fit, tic);
        }
    return fit;
}

}  // namespace vri::plot
