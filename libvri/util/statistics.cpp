#include "libvri/util/statistics.h"

#include <algorithm>
#include <cmath>

#include "libvri/util/error.h"

namespace vri {

double median(std::vector<double> values) {
    if (values.empty()) throw Error("median of no values");
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    if (values.size() % 2 == 1) return values[middle];
    return (values[middle - 1] + values[middle]) / 2;
}

double observedOrder(const std::vector<double>& steps, const std::vector<double>& errors) {
    if (steps.size() != errors.size() || steps.size() < 2)
        throw Error("an observed order needs two or more (step, error) pairs");
    const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!std::all_of(steps.begin(), steps.end(), positive) || !std::all_of(errors.begin(), errors.end(), positive))
        throw Error("an observed order needs positive, finite steps and errors");
    const double n = double(steps.size());
    double meanX = 0, meanY = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        meanX += std::log(steps[i]) / n;
        meanY += std::log(errors[i]) / n;
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const double dx = std::log(steps[i]) - meanX;
        sxy += dx * (std::log(errors[i]) - meanY);
        sxx += dx * dx;
    }
    if (!(sxx > 0.0)) throw Error("an observed order needs at least two different steps");
    return sxy / sxx;
}

}  // namespace vri
