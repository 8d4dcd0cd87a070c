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
// (gnuplot would extend it to whole decades, leaving most of a narrow chart empty). A log axis has no
// place for 0, and a 0 drawn as one more step down would read as a small count: values <= 0 go on a grey
// band at the bottom of the axis, kZeroBand of its length, below a break in the axis of kZeroGap, so that
// no line of the log range can be taken for it. Its one tic is labelled 0; the real tics start above the
// break. An axis spanning less than three decades is labelled at 1, 2 and 5 times each power of ten, under
// one decade at every digit (gnuplot would label only the powers, often one or none), one with a band at
// every power; a tic label nearer than kMinTicSpacing to the one below it (the band's 0 first) is left out,
// so that no two labels print over each other.
inline constexpr double kZeroBand = 0.05;  // fractions of the axis's length
inline constexpr double kZeroGap = 0.06;
inline constexpr double kMinTicSpacing = 0.04;  // about a label's height on a panel 300 pixels high
struct LogAxisFit {
    double min = 0, max = 0;
    double bottom = 0;           // where the positive values' range starts: min, or above the break
    std::optional<double> zero;  // where a value <= 0 is drawn (the band's middle); unset when the data have none
    std::vector<double> tics;    // besides the band's 0; empty: gnuplot's own (decades)
};
// Where a value lies along a fitted log axis, from 0 at its bottom to 1 at its top.
double axisFraction(const LogAxisFit& fit, double value);
// nullopt when no value is positive, or the spec gives the range.
std::optional<LogAxisFit> fitLogAxis(const PlotAxis& axis, const std::vector<double>& values);

}  // namespace vri::plot
