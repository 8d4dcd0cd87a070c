#include "vri/core/gauss_error_bound.h"

#include <algorithm>
#include <cmath>

namespace vri {

namespace {

constexpr int kOrders = 7;  // derivatives 0..6: the sixth is the 3-point rule's

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
    // The sums below are written out, term by term in the order of the sums they stand for (Leibniz's
    // rule, the Bell recurrence, the bounds), products left to right: loops over Pascal's triangle
    // left a chain of dependent loads and adds that cost more than the rest of the sub-piece's set-up.
    // Terms that a derivative of order 4 or more of a cubic zeroes are left out (adding +0 changes no
    // bit), and so are factors 1.
    // g's derivative bounds: C's, or Leibniz's rule on C tau, g_m = sum_i C(m, i) c_i t_(m - i).
    std::array<double, kOrders> g = c;
    if (colourTimesExtinction) {
        g[0] = c[0] * t[0];
        g[1] = c[0] * t[1] + c[1] * t[0];
        g[2] = c[0] * t[2] + 2.0 * c[1] * t[1] + c[2] * t[0];
        g[3] = c[0] * t[3] + 3.0 * c[1] * t[2] + 3.0 * c[2] * t[1] + c[3] * t[0];
        g[4] = 4.0 * c[1] * t[3] + 6.0 * c[2] * t[2] + 4.0 * c[3] * t[1];
        g[5] = 10.0 * c[2] * t[3] + 10.0 * c[3] * t[2];
        g[6] = 20.0 * c[3] * t[3];
    }
    // Y_m(d_1, ..., d_m) with d_j >= |D^(j)| = ell |tau^(j - 1)|: Y_0 = 1, Y_{m+1} = sum_i C(m, i) d_{i+1} Y_{m-i}.
    const double d0 = ell * t[0], d1 = ell * t[1], d2 = ell * t[2], d3 = ell * t[3];
    const double y1 = d0;
    const double y2 = d0 * y1 + d1;
    const double y3 = d0 * y2 + 2.0 * d1 * y1 + d2;
    const double y4 = d0 * y3 + 3.0 * d1 * y2 + 3.0 * d2 * y1 + d3;
    const double y5 = d0 * y4 + 4.0 * d1 * y3 + 6.0 * d2 * y2 + 4.0 * d3 * y1;
    const double y6 = d0 * y5 + 5.0 * d1 * y4 + 10.0 * d2 * y3 + 10.0 * d3 * y2;
    // |f^(2n)| <= sum_k C(2n, k) g_k Y_(2n - k), times the remainder constant of the n-point rule.
    const double f2 = g[0] * y2 + 2.0 * g[1] * y1 + g[2];
    const double f4 = g[0] * y4 + 4.0 * g[1] * y3 + 6.0 * g[2] * y2 + 4.0 * g[3] * y1 + g[4];
    const double f6 =
        g[0] * y6 + 6.0 * g[1] * y5 + 15.0 * g[2] * y4 + 20.0 * g[3] * y3 + 15.0 * g[4] * y2 + 6.0 * g[5] * y1 + g[6];
    return {transparencyMax * f2 * kRemainder[0], transparencyMax * f4 * kRemainder[1],
            transparencyMax * f6 * kRemainder[2]};
}

const GaussRule& gaussRule(int n) {
    static const GaussRule rules[3] = {
        {1, {0.5}, {1.0}},
        {2, {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}, {0.5, 0.5}},
        {3, {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)}, {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0}}};
    return rules[n - 1];
}

}  // namespace vri
