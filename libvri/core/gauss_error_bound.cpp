#include "libvri/core/gauss_error_bound.h"

#include <cmath>

#include "libvri/core/gauss_bound_kernel.h"
#include "libvri/core/scalar_double_ops.h"

namespace vri {

std::array<double, 3> gaussErrorBounds(const std::array<double, 4> (&colour)[3], const std::array<double, 4>& tau,
                                       bool colourTimesExtinction, double ell, double transparencyMax) {
    return gauss_bound_kernel::bounds(ScalarDoubleOps{}, colour, tau, colourTimesExtinction, ell, transparencyMax);
}

const GaussRule& gaussRule(int n) {
    static const GaussRule rules[3] = {
        {1, {0.5}, {1.0}},
        {2, {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}, {0.5, 0.5}},
        {3, {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)}, {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0}}};
    return rules[n - 1];
}

}  // namespace vri
