#pragma once
// The kernels' operations (gauss_bound_kernel.h, segment_kernel.h) on one double: the scalar code that
// the batches' lanes reproduce bit for bit.
#include <algorithm>
#include <cmath>

namespace vri {

struct ScalarDoubleOps {
    static double set(double c) { return c; }
    static double abs(double x) { return std::abs(x); }
    static double max(double a, double b) { return std::max(a, b); }
};

}  // namespace vri
