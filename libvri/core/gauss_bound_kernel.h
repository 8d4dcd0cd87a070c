// The derivative bounds behind gaussErrorBounds (gauss_error_bound.h), written once for any arithmetic:
// gauss_error_bound.cpp runs them on doubles, exact_gauss_batch.cpp on Highway vectors of doubles, one
// sub-piece per lane. Every lane performs the scalar code's operations in the same order, so both give
// the same bits. Ops supplies Real set(double), Real abs(Real), Real max(Real, Real); Real has + and *.
//
// Highway compiles a function for a target only where it is defined inside that target's region, so
// exact_gauss_batch.cpp includes this header there once per target (the guard toggles with Highway's,
// as in exp_kernel.h); other files include it once.
#if defined(VRI_GAUSS_BOUND_KERNEL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef VRI_GAUSS_BOUND_KERNEL_H_
#undef VRI_GAUSS_BOUND_KERNEL_H_
#else
#define VRI_GAUSS_BOUND_KERNEL_H_
#endif

#include <array>

namespace vri {
#ifdef HWY_NAMESPACE
namespace HWY_NAMESPACE {
#endif
namespace gauss_bound_kernel {

// |p^(j)| <= sum_i |p_i| i! / (i - j)! on [0, 1], for j = 0..3 (higher derivatives of a cubic vanish).
template <class Ops, class Real>
[[gnu::always_inline]] inline std::array<Real, 4> cubicDerivativeBounds(const Ops& o, const std::array<Real, 4>& p) {
    const Real a1 = o.abs(p[1]), a2 = o.abs(p[2]), a3 = o.abs(p[3]);
    const Real two = o.set(2.0), three = o.set(3.0), six = o.set(6.0);
    return {o.abs(p[0]) + a1 + a2 + a3, a1 + two * a2 + three * a3, two * a2 + six * a3, six * a3};
}

// See gaussErrorBounds.
template <class Ops, class Real>
[[gnu::always_inline]] inline std::array<Real, 3> bounds(const Ops& o, const std::array<Real, 4> (&colour)[3],
                                                        const std::array<Real, 4>& tau, bool colourTimesExtinction,
                                                        Real ell, Real transparencyMax) {
    // One bound for the three channels: C's derivative bounds are the largest channel's.
    std::array<Real, 4> c = cubicDerivativeBounds(o, colour[0]);
    for (int k = 1; k < 3; ++k) {
        const std::array<Real, 4> other = cubicDerivativeBounds(o, colour[k]);
        for (int j = 0; j < 4; ++j) c[j] = o.max(c[j], other[j]);
    }
    const std::array<Real, 4> t = cubicDerivativeBounds(o, tau);
    // The sums below are written out, term by term in the order of the sums they stand for (Leibniz's
    // rule, the Bell recurrence, the bounds), products left to right: loops over Pascal's triangle
    // left a chain of dependent loads and adds that cost more than the rest of the sub-piece's set-up.
    // Terms that a derivative of order 4 or more of a cubic zeroes are left out (adding +0 changes no
    // bit), and so are factors 1.
    const auto k = [&o](double v) { return o.set(v); };
    // g's derivative bounds: C's, or Leibniz's rule on C tau, g_m = sum_i C(m, i) c_i t_(m - i).
    Real g[7] = {c[0], c[1], c[2], c[3], k(0.0), k(0.0), k(0.0)};
    if (colourTimesExtinction) {
        g[0] = c[0] * t[0];
        g[1] = c[0] * t[1] + c[1] * t[0];
        g[2] = c[0] * t[2] + k(2.0) * c[1] * t[1] + c[2] * t[0];
        g[3] = c[0] * t[3] + k(3.0) * c[1] * t[2] + k(3.0) * c[2] * t[1] + c[3] * t[0];
        g[4] = k(4.0) * c[1] * t[3] + k(6.0) * c[2] * t[2] + k(4.0) * c[3] * t[1];
        g[5] = k(10.0) * c[2] * t[3] + k(10.0) * c[3] * t[2];
        g[6] = k(20.0) * c[3] * t[3];
    }
    // Y_m(d_1, ..., d_m) with d_j >= |D^(j)| = ell |tau^(j - 1)|: Y_0 = 1, Y_{m+1} = sum_i C(m, i) d_{i+1} Y_{m-i}.
    const Real d0 = ell * t[0], d1 = ell * t[1], d2 = ell * t[2], d3 = ell * t[3];
    const Real y1 = d0;
    const Real y2 = d0 * y1 + d1;
    const Real y3 = d0 * y2 + k(2.0) * d1 * y1 + d2;
    const Real y4 = d0 * y3 + k(3.0) * d1 * y2 + k(3.0) * d2 * y1 + d3;
    const Real y5 = d0 * y4 + k(4.0) * d1 * y3 + k(6.0) * d2 * y2 + k(4.0) * d3 * y1;
    const Real y6 = d0 * y5 + k(5.0) * d1 * y4 + k(10.0) * d2 * y3 + k(10.0) * d3 * y2;
    // |f^(2n)| <= sum_k C(2n, k) g_k Y_(2n - k), times the n-point rule's remainder on [0, 1] per unit
    // of |f^(2n)|, (n!)^4 / ((2n + 1) ((2n)!)^3).
    const Real f2 = g[0] * y2 + k(2.0) * g[1] * y1 + g[2];
    const Real f4 = g[0] * y4 + k(4.0) * g[1] * y3 + k(6.0) * g[2] * y2 + k(4.0) * g[3] * y1 + g[4];
    const Real f6 = g[0] * y6 + k(6.0) * g[1] * y5 + k(15.0) * g[2] * y4 + k(20.0) * g[3] * y3 + k(15.0) * g[4] * y2 +
                    k(6.0) * g[5] * y1 + g[6];
    return {transparencyMax * f2 * k(1.0 / 24.0), transparencyMax * f4 * k(1.0 / 4320.0),
            transparencyMax * f6 * k(1.0 / 2016000.0)};
}

}  // namespace gauss_bound_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_GAUSS_BOUND_KERNEL_H_
