#pragma once
// Private to vri-plot: the ranges of a panel's log axes fitted to the points it draws, and where a
// value of 0 goes on a log axis, which has no place for it.
#include <optional>
#include <utility>
#include <vector>

#include "libvri/report/plot.h"

namespace vri::plot {

// The points a series draws, in file order: its rows that `where` keeps and whose x and y read as
// finite numbers. For points and lines only (not histograms, heatmaps or segments).
std::vector<std::pair<double, double>> keptPoints(const PlotSeries& series);

// A log axis the spec leaves open ends a margin beyond the largest and smallest positive value drawn
// (gnuplot would extend it to whole decades, leaving most of a narrow chart empty). Values <= 0 are
// drawn on a floor: a line below the smallest positive value, labelled 0, with the axis ending a margin
// below it. An axis spanning less than three decades is labelled at 1, 2 and 5 times each power of ten,
// under one decade at every digit (gnuplot would label only the powers, often one or none).
struct LogAxisFit {
    double min = 0, max = 0;
    std::optional<double> floor;  // where a value <= 0 is drawn; unset when the data have none
    std::vector<double> tics;     // empty: gnuplot's own (decades)
};
// nullopt when no value is positive, or the spec gives the range.
std::optional<LogAxisFit> fitLogAxis(const PlotAxis& axis, const std::vector<double>& values);

}  // namespace vri::plot
