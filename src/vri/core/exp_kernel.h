// exp and expm1 in float from additions, subtractions and multiplications only, written once for any
// arithmetic: float_exp.cpp runs it on floats (the scalar fixed-step path), simd_march.cpp on Highway
// vectors (the packet engine). Every lane of a vector performs the scalar code's operations in the
// same order, so the two paths round alike and their images agree bit for bit; std::exp could not
// promise that, as its float result depends on the C library.
//
// Cody and Waite's reduction: x = k ln 2 + r with k = round(x / ln 2) and |r| <= ln 2 / 2, ln 2 split
// into a head with few bits (k * head is exact) and a tail. expm1(r) is its Taylor polynomial of
// degree 7, whose truncation error on |r| <= 0.347 is below 1e-8 (a quarter of a float ulp); then
// exp(x) = (1 + expm1(r)) 2^k and expm1(x) = 2^k expm1(r) + (2^k - 1), with no cancellation near 0.
//
// Ops supplies the few operations that differ between a float and a vector of floats:
//   Float set(float), Int setInt(int), Float select(Cond, Float, Float), Int toInt(Float) (exact on
//   integral values), Float pow2(Int k) (2^k for -126 <= k <= 127, from the exponent bits),
//   Int halve(Int) (arithmetic shift right by 1), Int clampInt(Int, int lo, int hi), Cond less(Float,
//   Float), Cond greater(Float, Float), Cond intGreater(Int, int), Cond isNaN(Float), and the Float
//   and Int operators + - *.
//
// Highway compiles a function for a target only where it is defined inside that target's region, so
// simd_march.cpp includes this header there once per target (the guard toggles with Highway's, as
// Highway's own -inl.h headers do), into that target's namespace; other files include it once.
#if defined(VRI_EXP_KERNEL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef VRI_EXP_KERNEL_H_
#undef VRI_EXP_KERNEL_H_
#else
#define VRI_EXP_KERNEL_H_
#endif

namespace vri {
#ifdef HWY_NAMESPACE
namespace HWY_NAMESPACE {
#endif
namespace exp_kernel {

constexpr float kLog2E = 1.44269504088896341f;
constexpr float kLn2Head = 0.693359375f;       // 0x3f318000: 9 significant bits
constexpr float kLn2Tail = -2.12194440e-4f;    // ln 2 - kLn2Head
constexpr float kRoundToInteger = 12582912.f;  // 1.5 * 2^23: (y + it) - it rounds |y| < 2^22 to an integer
// exp underflows to 0 below -103.97 and overflows above 88.73: clamping there changes no result
// and keeps k in [-150, 129].
constexpr float kLowest = -104.f;
constexpr float kHighest = 89.f;

template <class Ops, class Float>
struct Reduction {
    Float k;  // an integer, as a float
    Float r;  // x - k ln 2
};

template <class Ops, class Float>
[[gnu::always_inline]] inline Reduction<Ops, Float> reduce(const Ops& o, Float x) {
    // NaN compares false and becomes kLowest here; the callers put it back.
    const Float lowest = o.set(kLowest), highest = o.set(kHighest);
    Float xc = o.select(o.less(x, lowest), lowest, x);
    xc = o.select(o.greater(xc, highest), highest, xc);
    xc = o.select(o.isNaN(x), lowest, xc);
    const Float k = (xc * o.set(kLog2E) + o.set(kRoundToInteger)) - o.set(kRoundToInteger);
    const Float r = (xc - k * o.set(kLn2Head)) - k * o.set(kLn2Tail);
    return {k, r};
}

// expm1(r) for |r| <= ln 2 / 2: r + r^2 (1/2! + r (1/3! + ... + r / 7!)), Horner.
template <class Ops, class Float>
[[gnu::always_inline]] inline Float expm1Reduced(const Ops& o, Float r) {
    Float p = o.set(1.f / 5040.f);
    p = p * r + o.set(1.f / 720.f);
    p = p * r + o.set(1.f / 120.f);
    p = p * r + o.set(1.f / 24.f);
    p = p * r + o.set(1.f / 6.f);
    p = p * r + o.set(0.5f);
    return r + (r * r) * p;
}

template <class Ops, class Float>
[[gnu::always_inline]] inline Float exp(const Ops& o, Float x) {
    const Reduction<Ops, Float> red = reduce(o, x);
    const auto k = o.toInt(red.k);
    // 2^k in two factors, each a normal float for k in [-150, 129]; the first product is exact, so
    // a subnormal result is rounded once.
    const auto k1 = o.halve(k);
    const Float y = ((o.set(1.f) + expm1Reduced(o, red.r)) * o.pow2(k1)) * o.pow2(k - k1);
    return o.select(o.isNaN(x), x, y);
}

template <class Ops, class Float>
[[gnu::always_inline]] inline Float expm1(const Ops& o, Float x) {
    const Reduction<Ops, Float> red = reduce(o, x);
    const auto k = o.toInt(red.k);
    // Below k = -64, 2^k expm1(r) + (2^k - 1) rounds to -1 whatever r is, so k may be clamped there;
    // above k = 127 (x > 88.38) 2^k is not a float and expm1(x) = exp(x) to float precision.
    const Float scale = o.pow2(o.clampInt(k, -64, 127));
    const Float y = scale * expm1Reduced(o, red.r) + (scale - o.set(1.f));
    const Float big = exp(o, x);
    return o.select(o.isNaN(x), x, o.select(o.intGreater(k, 127), big, y));
}

}  // namespace exp_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_EXP_KERNEL_H_
