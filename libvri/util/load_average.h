#pragma once
// The machine's load: what else competed for its cores while a timed step ran.
#include <optional>

namespace vri {

// The 1-minute load average (/proc/loadavg's first field); nullopt where there is none to read.
std::optional<double> loadAverage();

}  // namespace vri
