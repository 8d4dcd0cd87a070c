// A sub-piece of the exact method (exact_ray.cpp) as its quadrature sees it: a transfer-function channel
// along it (v + m (s - sA) on its segment, with s a cubic in the sub-piece's variable, so a cubic too),
// the optical depth across it, and bounds on the emission and on their rounding.
// Written once for any arithmetic: exact_ray.cpp runs it on doubles, exact_gauss_batch.cpp on Highway
// vectors of doubles, one sub-piece per lane, in the same order, so every target gives the scalar code's
// bits. Ops supplies Real set(double) and Real abs(Real); Real has + - and *.
//
// Highway compiles a function for a target only where it is defined inside that target's region, so
// exact_gauss_batch.cpp includes this header there once per target (the guard toggles with Highway's, as
// in exp_kernel.h); other files include it once.
#if defined(VRI_SEGMENT_KERNEL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef VRI_SEGMENT_KERNEL_H_
#undef VRI_SEGMENT_KERNEL_H_
#else
#define VRI_SEGMENT_KERNEL_H_
#endif

#include <array>

namespace vri {
#ifdef HWY_NAMESPACE
namespace HWY_NAMESPACE {
#endif
namespace segment_kernel {

constexpr double kUnit = 0x1p-53;  // unit roundoff u of double

// The bound on the error of s's coefficients, given sScale (exact_ray.h): 32 u sScale.
template <class Ops, class Real>
[[gnu::always_inline]] inline Real coefficientError(const Ops& o, Real sScale) {
    return o.set(32.0 * kUnit) * sScale;
}

// The channel's coefficients p, the sum of their magnitudes (which bounds |p| on [0, 1]) and a bound on
// |computed - exact| anywhere on [0, 1].
template <class Real>
struct Linear {
    std::array<Real, 4> p;
    Real sum, error;
};

// c: s's coefficients, whose error is at most ds. Forming v + m (s - sA) and evaluating it by Horner adds
// at most 16 u (sum |p| + |v| + |m sA|) (the error analysis in exact_ray.cpp); s's error enters times |m|.
template <class Ops, class Real>
[[gnu::always_inline]] inline Linear<Real> alongSegment(const Ops& o, const std::array<Real, 4>& c, Real sA, Real v,
                                                        Real m, Real ds) {
    const Real p0 = v + m * (c[0] - sA), p1 = m * c[1], p2 = m * c[2], p3 = m * c[3];
    const Real sum = o.abs(p0) + o.abs(p1) + o.abs(p2) + o.abs(p3);
    return {{p0, p1, p2, p3}, sum, o.set(16.0 * kUnit) * (sum + o.abs(v) + o.abs(m * sA)) + o.abs(m) * ds};
}

// The optical depth from the sub-piece's start, ell times the integral of tau, a quartic in lambda with
// p[0] = 0, and a bound on its error at lambda = 1 (lambda times it at lambda).
template <class Real>
struct Depth {
    std::array<Real, 5> p;
    Real error;
};
template <class Ops, class Real>
[[gnu::always_inline]] inline Depth<Real> depthAlong(const Ops& o, const Linear<Real>& tau, Real ell) {
    Depth<Real> r;
    r.p[0] = o.set(0.0);
    for (int k = 0; k < 4; ++k) r.p[k + 1] = ell * tau.p[k] / o.set(k + 1.0);
    r.error = ell * (tau.error + o.set(8.0 * kUnit) * tau.sum);
    return r;
}

// Bounds on a channel's emission g (C tau, or C) and on its error where a rule evaluates it.
template <class Ops, class Real>
[[gnu::always_inline]] inline void emissionBounds(const Ops& o, const Linear<Real>& colour, const Linear<Real>& tau,
                                                  bool colourTimesExtinction, Real& gMax, Real& gError) {
    if (colourTimesExtinction) {
        gMax = colour.sum * tau.sum;
        gError = colour.error * tau.sum + colour.sum * tau.error + o.set(16.0 * kUnit) * gMax;
    } else {
        gMax = colour.sum;
        gError = colour.error;
    }
}

}  // namespace segment_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_SEGMENT_KERNEL_H_
