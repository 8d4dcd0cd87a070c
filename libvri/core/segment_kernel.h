// A transfer-function channel along a sub-piece of the exact method (exact_ray.cpp): the channel is
// v + m (s - sA) on its segment and s a cubic in the sub-piece's variable, so the channel is a cubic too.
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
    return {{p0, p1, p2, p3}, sum, o.set(16.0 * 0x1p-53) * (sum + o.abs(v) + o.abs(m * sA)) + o.abs(m) * ds};
}

}  // namespace segment_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_SEGMENT_KERNEL_H_
