#pragma once
// The per-ray log of the adaptive Simpson methods (vri-render --log-ray) as a CSV file.
#include <string>
#include <vector>

#include "libvri/core/adaptive_simpson.h"

namespace vri {

// The log as CSV: kind (inner/outer), accepted, skipped, t, h, t_end = t + h, error, tolerance, r, g, b, alpha,
// transparency (the last five after accepted outer tries, empty otherwise); numbers exact.
std::string adaptiveLogCsv(const std::vector<AdaptiveTry>& log);

}  // namespace vri
