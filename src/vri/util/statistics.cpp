#include "vri/util/statistics.h"

#include <algorithm>

#include "vri/util/error.h"

namespace vri {

double median(std::vector<double> values) {
    if (values.empty()) throw Error("median of no values");
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    if (values.size() % 2 == 1) return values[middle];
    return (values[middle - 1] + values[middle]) / 2;
}

}  // namespace vri
