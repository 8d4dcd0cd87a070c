#pragma once
// Summaries of repeated measurements (frame times, runs of a table cell) and of sweeps.
#include <vector>

namespace vri {

// Median of a non-empty list: the middle value, or the mean of the two middle ones.
double median(std::vector<double> values);

// The observed order of convergence of a sweep (Etiene et al.): the least-squares slope of log(error)
// against log(step). Throws vri::Error on fewer than two points, different lengths, a step or error
// that is not positive and finite, or steps that are all equal.
double observedOrder(const std::vector<double>& steps, const std::vector<double>& errors);

}  // namespace vri
