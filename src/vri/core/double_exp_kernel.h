// exp in double from additions, subtractions and multiplications only, written once for any
// arithmetic: the exact method's batched Gauss rules (exact_gauss_batch.cpp) run it on Highway vectors,
// one sub-piece per lane, and the unit test on doubles. Every lane performs the scalar code's operations
// in the same order and none is fused, so every Highway target rounds alike and the exact images do not
// depend on the CPU; std::exp could not promise that across C libraries.
//
// Cody and Waite's reduction, as in exp_kernel.h's float version: x = k ln 2 + r with k = round(x / ln 2)
// and |r| <= ln 2 / 2 (to rounding), ln 2 split into a head whose low 21 bits are zero (k * head is
// exact for |k| < 2^21) and a tail. expm1(r) is its Taylor polynomial of degree 13, whose truncation
// error on |r| <= 0.3466 is below 5e-18 relative (1/25 of a double ulp); then exp(x) = (1 + expm1(r)) 2^k
// with 2^k in two factors, so that a subnormal result is rounded once. Measured against long double
// (tests/unit/double_exp_test.cpp): within 1 ulp where the result is normal.
//
// Ops supplies Real set(double), Int toInt(Real) (exact on integral values), Real pow2(Int k) (2^k
// for -1022 <= k <= 1023, from the exponent bits), Int halve(Int) (arithmetic shift right by 1),
// Real select(Cond, Real, Real), Cond less(Real, Real), Cond greater(Real, Real), Cond isNaN(Real),
// and the Real operators + - * and Int -.
#if defined(VRI_DOUBLE_EXP_KERNEL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef VRI_DOUBLE_EXP_KERNEL_H_
#undef VRI_DOUBLE_EXP_KERNEL_H_
#else
#define VRI_DOUBLE_EXP_KERNEL_H_
#endif

namespace vri {
#ifdef HWY_NAMESPACE
namespace HWY_NAMESPACE {
#endif
namespace double_exp_kernel {

constexpr double kLog2E = 1.4426950408889634074;
constexpr double kLn2Head = 6.93147180369123816490e-01;  // 0x3fe62e42fee00000
constexpr double kLn2Tail = 1.90821492927058770002e-10;  // ln 2 - kLn2Head
constexpr double kRoundToInteger = 6755399441055744.0;  // 1.5 * 2^52: (y + it) - it rounds |y| < 2^51
// exp underflows to 0 below -745.14 and overflows above 709.79: clamping there changes no result and
// keeps k in [-1076, 1025], whose halves are normal powers of two.
constexpr double kLowest = -746.0;
constexpr double kHighest = 710.0;

template <class Ops, class Real>
[[gnu::always_inline]] inline Real exp(const Ops& o, Real x) {
    // NaN compares false and becomes kLowest here; the end puts it back.
    const Real lowest = o.set(kLowest), highest = o.set(kHighest);
    Real xc = o.select(o.less(x, lowest), lowest, x);
    xc = o.select(o.greater(xc, highest), highest, xc);
    xc = o.select(o.isNaN(x), lowest, xc);
    const Real k = (xc * o.set(kLog2E) + o.set(kRoundToInteger)) - o.set(kRoundToInteger);
    const Real r = (xc - k * o.set(kLn2Head)) - k * o.set(kLn2Tail);
    // expm1(r) = r + r^2 (1/2! + r (1/3! + ... + r / 13!)), Horner.
    Real p = o.set(1.0 / 6227020800.0);
    p = p * r + o.set(1.0 / 479001600.0);
    p = p * r + o.set(1.0 / 39916800.0);
    p = p * r + o.set(1.0 / 3628800.0);
    p = p * r + o.set(1.0 / 362880.0);
    p = p * r + o.set(1.0 / 40320.0);
    p = p * r + o.set(1.0 / 5040.0);
    p = p * r + o.set(1.0 / 720.0);
    p = p * r + o.set(1.0 / 120.0);
    p = p * r + o.set(1.0 / 24.0);
    p = p * r + o.set(1.0 / 6.0);
    p = p * r + o.set(0.5);
    const Real expm1 = r + (r * r) * p;
    const auto ki = o.toInt(k);
    const auto k1 = o.halve(ki);
    const Real y = ((o.set(1.0) + expm1) * o.pow2(k1)) * o.pow2(ki - k1);
    return o.select(o.isNaN(x), x, y);
}

}  // namespace double_exp_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_DOUBLE_EXP_KERNEL_H_
