// exp (and expm1 in float) from additions, subtractions and multiplications only, written once for any
// arithmetic and for float and double: float_exp.cpp runs it on floats (the scalar fixed-step path),
// simd_march.cpp on Highway vectors of floats (the packet engine), exact_gauss_batch.cpp on vectors of
// doubles (the exact method's batched Gauss rules). Every lane of a vector performs the scalar code's
// operations in the same order, unfused, so the two paths round alike and their images agree bit for bit
// on every target; std::exp could not promise that, as its result depends on the C library.
//
// Cody and Waite's reduction: x = k ln 2 + r with k = round(x / ln 2) and |r| <= ln 2 / 2, ln 2 split
// into a head with few bits (k * head is exact) and a tail. expm1(r) is its Taylor polynomial, of degree
// 7 in float (truncation error on |r| <= 0.347 below 1e-8, a quarter of a float ulp) and 13 in double
// (below 5e-18 relative, 1/25 of a double ulp); then exp(x) = (1 + expm1(r)) 2^k, with 2^k in two
// factors so that a subnormal result is rounded once, and expm1(x) = 2^k expm1(r) + (2^k - 1), with no
// cancellation near 0.
//
// Ops supplies the few operations that differ between a number and a vector: the type Scalar (float or
// double, which picks the constants), Real set(Scalar), Int setInt(int), Real select(Cond, Real, Real),
// Int toInt(Real) (exact on integral values within exp's range of k), Real pow2(Int k) (2^k for a normal
// power of two, from the exponent bits), Int halve(Int) (arithmetic shift right by 1), Int clampInt(Int,
// int lo, int hi), Real clamp(Real x, Real lo, Real hi) (x < lo ? lo : x > hi ? hi : x for any x but NaN:
// a vector's min and max), Cond intGreater(Int, int), Cond isNaN(Real), and the Real and Int operators
// + - *. (expm1 is float only; exp needs neither setInt, clampInt nor intGreater.)
//
// Highway compiles a function for a target only where it is defined inside that target's region, so
// simd_march.cpp and exact_gauss_batch.cpp include this header there once per target (the guard toggles
// with Highway's, as Highway's own -inl.h headers do), into that target's namespace; other files include
// it once.
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

// Each precision's constants. exp underflows to 0 below `lowest` and overflows above `highest`: clamping
// there changes no result and keeps k where its halves are normal powers of two.
template <class Scalar>
struct Constants;
template <>
struct Constants<float> {
    static constexpr float log2E = 1.44269504088896341f;
    static constexpr float ln2Head = 0.693359375f;       // 0x3f318000: 9 significant bits
    static constexpr float ln2Tail = -2.12194440e-4f;    // ln 2 - ln2Head
    static constexpr float roundToInteger = 12582912.f;  // 1.5 * 2^23: (y + it) - it rounds |y| < 2^22 to an integer
    static constexpr float lowest = -104.f;              // exp(-103.97) underflows; k in [-150, 129]
    static constexpr float highest = 89.f;               // exp(88.73) overflows
};
template <>
struct Constants<double> {
    static constexpr double log2E = 1.4426950408889634074;
    static constexpr double ln2Head = 6.93147180369123816490e-01;  // 0x3fe62e42fee00000: low 21 bits zero
    static constexpr double ln2Tail = 1.90821492927058770002e-10;  // ln 2 - ln2Head
    static constexpr double roundToInteger = 6755399441055744.0;   // 1.5 * 2^52: rounds |y| < 2^51
    static constexpr double lowest = -746.0;                       // exp(-745.14) underflows; k in [-1076, 1025]
    static constexpr double highest = 710.0;                       // exp(709.79) overflows
};

template <class Ops, class Real>
struct Reduction {
    Real k;  // an integer, as a Real
    Real r;  // x - k ln 2
};

// Clamp false: the caller knows x lies in [C::lowest, C::highest], where the clamp is the identity.
template <bool Clamp = true, class Ops, class Real>
[[gnu::always_inline]] inline Reduction<Ops, Real> reduce(const Ops& o, Real x) {
    using C = Constants<typename Ops::Scalar>;
    Real xc = x;
    if constexpr (Clamp) {
        // NaN compares false and becomes C::lowest here; the callers put it back.
        const Real lowest = o.set(C::lowest), highest = o.set(C::highest);
        xc = o.select(o.isNaN(x), lowest, o.clamp(x, lowest, highest));
    }
    const Real k = (xc * o.set(C::log2E) + o.set(C::roundToInteger)) - o.set(C::roundToInteger);
    const Real r = (xc - k * o.set(C::ln2Head)) - k * o.set(C::ln2Tail);
    return {k, r};
}

// expm1(r) for |r| <= ln 2 / 2: r + r^2 (1/2! + r (1/3! + ... + r / 7!)) in float, to r / 13! in
// double, Horner.
template <class Ops, class Real>
[[gnu::always_inline]] inline Real expm1Reduced(const Ops& o, Real r) {
    using Scalar = typename Ops::Scalar;
    Real p;
    if constexpr (sizeof(Scalar) == sizeof(double)) {
        p = o.set(1.0 / 6227020800.0);
        p = p * r + o.set(1.0 / 479001600.0);
        p = p * r + o.set(1.0 / 39916800.0);
        p = p * r + o.set(1.0 / 3628800.0);
        p = p * r + o.set(1.0 / 362880.0);
        p = p * r + o.set(1.0 / 40320.0);
        p = p * r + o.set(1.0 / 5040.0);
    } else {
        p = o.set(Scalar(1) / Scalar(5040));
    }
    p = p * r + o.set(Scalar(1) / Scalar(720));
    p = p * r + o.set(Scalar(1) / Scalar(120));
    p = p * r + o.set(Scalar(1) / Scalar(24));
    p = p * r + o.set(Scalar(1) / Scalar(6));
    p = p * r + o.set(Scalar(0.5));
    return r + (r * r) * p;
}

template <class Ops, class Real>
[[gnu::always_inline]] inline Real exp(const Ops& o, Real x) {
    const Reduction<Ops, Real> red = reduce(o, x);
    const auto k = o.toInt(red.k);
    // 2^k in two factors, each a normal power of two for k between C::lowest and C::highest over ln 2;
    // the first product is exact, so a subnormal result is rounded once.
    const auto k1 = o.halve(k);
    const Real y = ((o.set(1) + expm1Reduced(o, red.r)) * o.pow2(k1)) * o.pow2(k - k1);
    return o.select(o.isNaN(x), x, y);
}

// Where exp(x) is a normal float, x in [-kNormalRange, 0], exp()'s result without its clamp, NaN's
// selects and the split of 2^k: k >= -124, so 2^k is a normal power of two and 1 + expm1(r) >= 0.7 times
// it is normal too; a product by a power of two is then exact, in one factor as in two.
inline constexpr double kNormalRange = 86.0;  // x log2 e >= -124.1

template <class Ops, class Real>
[[gnu::always_inline]] inline Real expInNormalRange(const Ops& o, Real x) {
    const Reduction<Ops, Real> red = reduce<false>(o, x);
    return (o.set(1) + expm1Reduced(o, red.r)) * o.pow2(o.toInt(red.k));
}

// Within kNearZero of 0 the reduction is the identity: x log2 e rounds to k = 0 (|x log2 e| <= 0.4905),
// so r = (x - 0) - 0 = x (but for -0, which both polynomials take to +0), 2^k = 1 and (scale - 1) = 0.
// There exp(x) = 1 + expm1Reduced(x) and expm1(x) = expm1Reduced(x), bit for bit, without the reduction,
// the clamps or the powers of two: a step of a fixed-step ray rarely dims it by more than e^-0.34.
inline constexpr double kNearZero = 0.34;

template <class Ops, class Real>
[[gnu::always_inline]] inline Real expNearZero(const Ops& o, Real x) {
    return o.set(1) + expm1Reduced(o, x);
}

template <class Ops, class Real>
[[gnu::always_inline]] inline Real expm1NearZero(const Ops& o, Real x) {
    return expm1Reduced(o, x);
}

// expm1 from its reduction: 2^k expm1(r) + (2^k - 1). Below k = -64 that rounds to -1 whatever r is, so
// k may be clamped there; above k = 127 (x > 88.38) 2^k is not a float, and expm1() takes exp() instead.
template <class Ops, class Int, class Float>
[[gnu::always_inline]] inline Float expm1FromReduction(const Ops& o, Int k, Float r) {
    static_assert(sizeof(typename Ops::Scalar) == sizeof(float), "the clamps are float's");
    const Float scale = o.pow2(o.clampInt(k, -64, 127));
    return scale * expm1Reduced(o, r) + (scale - o.set(1.f));
}

// expm1(x) for x in [-kNormalRange, 0]: expm1()'s result without its clamp, NaN's selects and exp()
// for k above 127.
template <class Ops, class Float>
[[gnu::always_inline]] inline Float expm1InNormalRange(const Ops& o, Float x) {
    const Reduction<Ops, Float> red = reduce<false>(o, x);
    return expm1FromReduction(o, o.toInt(red.k), red.r);
}

template <class Ops, class Float>
[[gnu::always_inline]] inline Float expm1(const Ops& o, Float x) {
    const Reduction<Ops, Float> red = reduce(o, x);
    const auto k = o.toInt(red.k);
    const Float y = expm1FromReduction(o, k, red.r);
    const Float big = exp(o, x);
    return o.select(o.isNaN(x), x, o.select(o.intGreater(k, 127), big, y));
}

}  // namespace exp_kernel
#ifdef HWY_NAMESPACE
}  // namespace HWY_NAMESPACE
#endif
}  // namespace vri

#endif  // VRI_EXP_KERNEL_H_
