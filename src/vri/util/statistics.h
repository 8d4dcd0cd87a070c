#pragma once
// Summaries of repeated measurements (frame times, runs of a table cell).
#include <vector>

namespace vri {

// Median of a non-empty list: the middle value, or the mean of the two middle ones.
double median(std::vector<double> values);

}  // namespace vri
