// The float exp and expm1 shared by the scalar float path and the packet engine (float_exp.h) against
// the C library's double functions: the error in float ulps of the exact value over the whole range
// where the result is a normal float, the subnormal range, and the edges; and exp_kernel.h's short forms
// against its full ones.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include "libvri/core/exp_kernel.h"
#include "libvri/core/float_exp.h"
#include "libvri/core/scalar_exp_ops.h"

using namespace vri;

namespace {

// |got - exact| in units of the float spacing at `exact` (2^-149 for subnormal values).
double ulpError(float got, double exact) {
    const int exponent = std::max(std::ilogb(exact), -126);
    return std::abs(static_cast<double>(got) - exact) / std::ldexp(1.0, exponent - 23);
}

// 2^21 + 1 floats evenly spread over [lo, hi], and every float within 4096 steps of 0 and of the ends.
template <class Visit>
void manyFloats(float lo, float hi, const Visit& visit) {
    constexpr int n = 1 << 21;
    for (int i = 0; i <= n; ++i)
        visit(static_cast<float>(lo + (static_cast<double>(hi) - lo) * i / n));
    for (float x : {lo, hi, 0.f}) {
        float up = x, down = x;
        for (int i = 0; i < 4096; ++i) {
            up = std::nextafter(up, hi);
            down = std::nextafter(down, lo);
            visit(up);
            visit(down);
        }
    }
}

}  // namespace

TEST_CASE("expFloat is within 1.01 ulp of exp wherever the result is a normal float") {
    double worst = 0, worstAt = 0;
    manyFloats(-87.3f, 88.7f, [&](float x) {
        const double e = ulpError(expFloat(x), std::exp(static_cast<double>(x)));
        if (e > worst) worst = e, worstAt = x;
    });
    MESSAGE("expFloat: largest error ", worst, " ulp at x = ", worstAt);
    CHECK(worst <= 1.01);  // 1.005 measured, at x = 48.18
}

TEST_CASE("expFloat rounds subnormal results to within 1 subnormal step and underflows to 0") {
    double worst = 0;
    for (float x = -87.4f; x > -103.9f; x -= 0.0137f)
        worst = std::max(worst, ulpError(expFloat(x), std::exp(double(x))));
    MESSAGE("expFloat subnormal: largest error ", worst, " x 2^-149");
    CHECK(worst <= 1.0);
    CHECK(expFloat(-103.8f) > 0.f);
    CHECK(expFloat(-104.f) == 0.f);
    CHECK(expFloat(-1000.f) == 0.f);
    CHECK(expFloat(-std::numeric_limits<float>::infinity()) == 0.f);
    CHECK(!std::signbit(expFloat(-1000.f)));
}

TEST_CASE("expFloat at the edges: 0, overflow, infinities, NaN") {
    CHECK(expFloat(0.f) == 1.f);
    CHECK(expFloat(-0.f) == 1.f);
    CHECK(expFloat(88.72f) < std::numeric_limits<float>::infinity());
    CHECK(expFloat(88.73f) == std::numeric_limits<float>::infinity());
    CHECK(expFloat(1e30f) == std::numeric_limits<float>::infinity());
    CHECK(expFloat(std::numeric_limits<float>::infinity()) == std::numeric_limits<float>::infinity());
    CHECK(std::isnan(expFloat(std::numeric_limits<float>::quiet_NaN())));
    CHECK(expFloat(1.f) == doctest::Approx(std::exp(1.0)).epsilon(1e-7));
}

TEST_CASE("expm1Float is within 2 ulp of expm1 and keeps tiny arguments exact") {
    double worst = 0, worstAt = 0;
    manyFloats(-100.f, 88.7f, [&](float x) {
        const double e = ulpError(expm1Float(x), std::expm1(static_cast<double>(x)));
        if (e > worst) worst = e, worstAt = x;
    });
    MESSAGE("expm1Float: largest error ", worst, " ulp at x = ", worstAt);
    CHECK(worst <= 2.0);  // 1.66 measured, at x = 0.352
    for (float tiny : {1e-30f, -1e-30f, 1e-10f, -3e-8f, std::numeric_limits<float>::denorm_min()})
        CHECK(expm1Float(tiny) == tiny);
    CHECK(expm1Float(0.f) == 0.f);
    CHECK(expm1Float(-1000.f) == -1.f);
    CHECK(expm1Float(-std::numeric_limits<float>::infinity()) == -1.f);
    CHECK(expm1Float(88.73f) == std::numeric_limits<float>::infinity());
    CHECK(expm1Float(std::numeric_limits<float>::infinity()) == std::numeric_limits<float>::infinity());
    CHECK(std::isnan(expm1Float(std::numeric_limits<float>::quiet_NaN())));
}

TEST_CASE("exp_kernel's short forms give exp's and expm1's bits where they hold") {
    // The packet engine picks a short form per packet from the deepest step it can take; each must
    // round exactly as the full function over its range (sampled densely here, with its ends), or images
    // would change. The commonest argument of all, -0 (tau = 0), and +0 too, by name.
    const ScalarExpOps o;
    const auto same = [](float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); };
    long checked = 0, differ = 0;
    const float nearZero = static_cast<float>(exp_kernel::kNearZero);
    manyFloats(-nearZero, nearZero, [&](float x) {
        ++checked;
        differ += !same(exp_kernel::expNearZero(o, x), exp_kernel::exp(o, x));
        differ += !same(exp_kernel::expm1NearZero(o, x), exp_kernel::expm1(o, x));
    });
    manyFloats(-static_cast<float>(exp_kernel::kNormalRange), 0.f, [&](float x) {
        ++checked;
        differ += !same(exp_kernel::expInNormalRange(o, x), exp_kernel::exp(o, x));
        differ += !same(exp_kernel::expm1InNormalRange(o, x), exp_kernel::expm1(o, x));
    });
    for (float zero : {-0.f, 0.f}) {
        CHECK(same(exp_kernel::expNearZero(o, zero), exp_kernel::exp(o, zero)));
        CHECK(same(exp_kernel::expm1NearZero(o, zero), exp_kernel::expm1(o, zero)));
        CHECK(same(exp_kernel::expInNormalRange(o, zero), exp_kernel::exp(o, zero)));
        CHECK(same(exp_kernel::expm1InNormalRange(o, zero), exp_kernel::expm1(o, zero)));
    }
    MESSAGE(checked, " arguments");
    CHECK(differ == 0);
    // Not a blank test: past its range a short form rounds differently (here no longer exp at all).
    CHECK(!same(exp_kernel::expNearZero(o, -1.f), exp_kernel::exp(o, -1.f)));
    CHECK(!same(exp_kernel::expInNormalRange(o, -100.f), exp_kernel::exp(o, -100.f)));
}
