#include "libvri/util/load_average.h"

#include <fstream>

namespace vri {

std::optional<double> loadAverage() {
    std::ifstream file("/proc/loadavg");
    double oneMinute = 0;
    if (!(file >> oneMinute)) return std::nullopt;
    return oneMinute;
}

}  // namespace vri
