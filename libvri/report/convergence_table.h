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

// One row per series (in order of first appearance): "points" (h values), "h max", "h min", the largest
// error at each ("error at h max", "error at h min", or of the one point without a step), "observed
// order" (log of the error ratio over log of the step ratio of the two smallest h above the floor),
// "fitted slope" (the least-squares slope over every point above the floor, observedOrder) and "error
// bound" (the largest stats.error_bound.max of the series, where the stats have one). Throws vri::Error
// naming the file when a diff lacks channels, a step is not positive or a series mixes runs with and
// without a step.
Table convergenceTable(const std::vector<ConvergencePoint>& points, double floor = kConvergenceFloor);

// The points for a log-log plot, one row per point with a step and an error above the floor:
// series,h,error,legend; legend is "SERIES: slope P" (or "SERIES" where no slope was fitted), so a
// plot's key shows the fitted slope of each series (vri-plot's `label_from: legend`).
std::string convergencePointsCsv(const std::vector<ConvergencePoint>& points, double floor = kConvergenceFloor);

}  // namespace vri
