#pragma once
// `vri-run --new NAME`: the three files of a small study to start an own one from, commented, that run
// as written anywhere (an analytic field, no data set): NAME.yaml (the experiment: an exact reference,
// Riemann and coupled adaptive Simpson sweeps, a speed-against-accuracy table and its chart),
// NAME-tf.yaml (a transfer function) and NAME-plot.yaml (the chart's vri-plot spec).
#include <filesystem>
#include <vector>

namespace vri {

// Writes the files beside `path` (its folder, NAME its file name without .yaml, a safe name), the
// experiment last, and returns them in that order; refuses, writing nothing, when NAME is not a safe name or
// one of them exists, and places none of them when a write fails (a full disk).
std::vector<std::filesystem::path> writeNewStudy(const std::filesystem::path& path);

}  // namespace vri
