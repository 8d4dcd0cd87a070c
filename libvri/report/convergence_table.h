#pragma once
// Observed orders of convergence (Etiene et al.) from a step sweep: per series of runs that differ
// only in their step h, the largest error against the accurate reference at each h and the slope p of
// log(error) against log(h), read from the vri-diff JSON of each run (and its stats for an error bound).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "libvri/report/table.h"

namespace vri {

struct ConvergencePoint {
    std::string series;           // the runs of one method, placement and scene: "ramp-riemann-eye"
    std::optional<double> step;   // h in voxels; none for a run without a step (the exact method)
    std::filesystem::path diff;   // vri-diff --json of the run against the reference
    std::filesystem::path stats;  // the run's stats: stats.error_bound.max where it has one (vri-reference)
};

// Errors at or below the floor are float32 rounding of the images, not the method's: left out of the fit.
inline constexpr double kConvergenceFloor = 1e-6;
// A mean error's floor: float32 rounds a value below 1 by at most 2^-24, a difference of two images by
// 2^-23, and a mean of such roundings no more.
inline constexpr double kConvergenceMeanFloor = 0x1p-23;
// The fit's asymptotic range: the smallest steps, where the leading error term dominates. Three steps
// (two halvings) let the fit show whether the order holds, where two would give one local order only;
// larger steps are tabulated and plotted but not fitted.
inline constexpr std::size_t kConvergenceFitSteps = 3;

// One row per series (in order of first appearance): "points" (h values), "h max", "h min", the largest
// and the mean error at h max and h min (or of the one point without a step, in the h min columns),
// "max order" and "mean order" (the least-squares slopes of log error against log h, observedOrder, over
// the kConvergenceFitSteps smallest steps whose error is above its floor: `floor` for the max,
// kConvergenceMeanFloor for the mean), "max fitted from h" and "mean fitted from h" (the largest step of
// each range) and "error bound" (the largest stats.error_bound.max of the series, where
// the stats have one). Throws vri::Error naming the file when a diff lacks channels or their max_abs or
// mean_abs, a step is not positive or a series mixes runs with and without a step.
Table convergenceTable(const std::vector<ConvergencePoint>& points, double floor = kConvergenceFloor);

// The points for a log-log plot, one row per point with a step and an error above the floor:
// series,h,error,legend with the largest error; legend is "SERIES: max order P" (or "SERIES" where no
// order was fitted), so a plot's key shows each series' order (vri-plot's `label_from: legend`).
std::string convergencePointsCsv(const std::vector<ConvergencePoint>& points, double floor = kConvergenceFloor);

}  // namespace vri
