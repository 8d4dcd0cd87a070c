#include "libvri/util/format.h"

#include <charconv>
#include <cmath>

namespace vri {

std::string exactNumber(double value) {
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (std::isnan(value)) return "nan";
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest round trip
    return std::string(buffer, end);
}

}  // namespace vri
