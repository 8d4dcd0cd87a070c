#include "vri/core/gauss_error_bound.h"

#include <algorithm>
#include <cmath>

namespace vri {

namespace {

constexpr int kOrders = 7;  // derivatives 0..6: the sixth is the 3-point rule's

// Pascal's triangle, C(m, i) for m < kOrders.
constexpr std::array<std::array<double, kOrders>, kOrders> kBinomial = [] {
    std::array<std::array<double, kOrders>, kOrders> b{};
    for (int m = 0; m < kOrders; ++m) {
        b[m][0] = 1.0;
        for (int i = 1; i <= m; ++i) b[m][i] = b[m - 1][i - 1] + (i < m ? b[m - 1][i] : 0.0);
    }
    return b;
}();

// The n-point rule's remainder on [0, 1] per unit of |f^(2n)|: (n!)^4 / ((2n + 1) ((2n)!)^3).
constexpr double kRemainder[3] = {1.0 / 24.0, 1.0 / 4320.0, 1.0 / 2016000.0};

// |p^(j)| <= sum_i |p_i| i! / (i - j)! on [0, 1], for j = 0..3 (higher derivatives of a cubic vanish).
std::array<double, kOrders> cubicDerivativeBounds(const std::array<double, 4>& p) {
    const double a1 = std::abs(p[1]), a2 = std::abs(p[2]), a3 = std::abs(p[3]);
    return {std::abs(p[0]) + a1 + a2 + a3, a1 + 2.0 * a2 + 3.0 * a3, 2.0 * a2 + 6.0 * a3, 6.0 * a3, 0.0, 0.0, 0.0};
}

}  // namespace

std::array<double, 3> gaussErrorBounds(const std::array<double, 4> (&colour)[3], const std::array<double, 4>& tau,
                                       bool colourTimesExtinction, double ell, double transparencyMax) {
    // One bound for the three channels: C's derivative bounds are the largest channel's.
    std::array<double, kOrders> c = cubicDerivativeBounds(colour[0]);
    for (int k = 1; k < 3; ++k) {
        const std::array<double, kOrders> other = cubicDerivativeBounds(colour[k]);
        for (int j = 0; j < 4; ++j) c[j] = std::max(c[j], other[j]);
    }
    const std::array<double, kOrders> t = cubicDerivativeBounds(tau);
    // g's derivative bounds: C's, or Leibniz's rule on C tau. Its terms with a derivative of order 4
    // or more of a cubic are zero: the unrolled loops leave them out (adding +0 changes no bit).
    std::array<double, kOrders> g = c;
    if (colourTimesExtinction) {
#pragma GCC unroll 7
        for (int m = 0; m < kOrders; ++m) {
            double r = 0.0;
#pragma GCC unroll 4
            for (int i = std::max(0, m - 3); i <= std::min(m, 3); ++i) r += kBinomial[m][i] * c[i] * t[m - i];
            g[m] = r;
        }
    }
    // Y_m(d_1, ..., d_m) with d_j >= |D^(j)| = ell |tau^(j - 1)|: Y_0 = 1, Y_{m+1} = sum_i C(m, i) d_{i+1} Y_{m-i}.
    const std::array<double, 4> d = {ell * t[0], ell * t[1], ell * t[2], ell * t[3]};
    std::array<double, kOrders> y{};
    y[0] = 1.0;
#pragma GCC unroll 6
    for (int m = 0; m + 1 < kOrders; ++m) {
        double r = 0.0;
#pragma GCC unroll 4
        for (int i = 0; i < 4; ++i)
            if (i <= m) r += kBinomial[m][i] * d[i] * y[m - i];
        y[m + 1] = r;
    }
    std::array<double, 3> bound{};
#pragma GCC unroll 3
    for (int n = 1; n <= 3; ++n) {  // |f^(2n)| times the remainder constant of the n-point rule
        double r = 0.0;
#pragma GCC unroll 7
        for (int k = 0; k <= 2 * n; ++k) r += kBinomial[2 * n][k] * g[k] * y[2 * n - k];
        bound[n - 1] = transparencyMax * r * kRemainder[n - 1];
    }
    return bound;
}

const GaussRule& gaussRule(int n) {
    static const GaussRule rules[3] = {
        {1, {0.5}, {1.0}},
        {2, {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}, {0.5, 0.5}},
        {3, {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)}, {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0}}};
    return rules[n - 1];
}

}  // namespace vri
