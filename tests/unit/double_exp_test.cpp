// The double exp of the exact method's batched Gauss rules (exp_kernel.h), run on doubles as the
// vector code runs it on each lane, against long double's expl: the error in double ulps of the exact
// value wherever the result is normal, the subnormal range, and the edges.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "libvri/core/exp_kernel.h"

using namespace vri;

namespace {

// exp_kernel.h's operations on one double.
struct ScalarOps {
    using Scalar = double;
    static double set(double c) { return c; }
    static double select(bool c, double a, double b) { return c ? a : b; }
    static double clamp(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }
    static bool isNaN(double x) { return x != x; }
    static std::int64_t toInt(double k) { return static_cast<std::int64_t>(k); }
    static std::int64_t halve(std::int64_t k) { return k >> 1; }  // arithmetic in C++20
    static double pow2(std::int64_t k) { return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52); }
};

double expDouble(double x) { return exp_kernel::exp(ScalarOps{}, x); }

// |got - exact| in units of the double spacing at `exact` (2^-1074 for subnormal values).
double ulpError(double got, long double exact) {
    const int exponent = std::max(std::ilogb(static_cast<double>(exact)), -1022);
    return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / std::ldexp(1.0L, exponent - 52));
}

}  // namespace

TEST_CASE("double exp kernel: within 1 ulp wherever the result is a normal double") {
    static_assert(std::numeric_limits<long double>::digits >= 64, "expl must be more precise than double");
    std::mt19937_64 rng(17);
    double worst = 0, worstAt = 0;
    auto visit = [&](double x) {
        const double e = ulpError(expDouble(x), std::exp(static_cast<long double>(x)));
        if (e > worst) worst = e, worstAt = x;
    };
    // The optical depths the exact method meets, densely, and the whole normal range.
    std::uniform_real_distribution<double> depths(-50.0, 0.5), all(-708.3, 709.7), tiny(-1e-6, 1e-6);
    for (int i = 0; i < 1 << 20; ++i) visit(depths(rng));
    for (int i = 0; i < 1 << 19; ++i) visit(all(rng));
    for (int i = 0; i < 1 << 16; ++i) visit(tiny(rng));
    // Where the reduction changes k: near multiples of ln 2 / 2.
    for (int k = -2000; k <= 2000; ++k) {
        const double x = k * 0.34657359027997264;
        if (x > -708.3 && x < 709.7)
            for (double y : {std::nextafter(x, -1e9), x, std::nextafter(x, 1e9)}) visit(y);
    }
    MESSAGE("double exp: largest error ", worst, " ulp at x = ", worstAt);
    CHECK(worst <= 1.0);
}

TEST_CASE("double exp kernel: subnormal results within 1 step, underflow to +0, overflow, NaN") {
    double worst = 0;
    for (double x = -708.4; x > -745.1; x -= 0.0137) worst = std::max(worst, ulpError(expDouble(x), std::exp(static_cast<long double>(x))));
    MESSAGE("double exp subnormal: largest error ", worst, " x 2^-1074");
    CHECK(worst <= 1.0);
    CHECK(expDouble(-745.0) > 0.0);
    CHECK(expDouble(-745.2) == 0.0);
    CHECK(expDouble(-1e300) == 0.0);
    CHECK(!std::signbit(expDouble(-1e300)));
    CHECK(expDouble(-std::numeric_limits<double>::infinity()) == 0.0);
    CHECK(expDouble(0.0) == 1.0);
    CHECK(expDouble(-0.0) == 1.0);
    CHECK(expDouble(709.7) < std::numeric_limits<double>::infinity());
    CHECK(expDouble(709.8) == std::numeric_limits<double>::infinity());
    CHECK(expDouble(std::numeric_limits<double>::infinity()) == std::numeric_limits<double>::infinity());
    CHECK(std::isnan(expDouble(std::numeric_limits<double>::quiet_NaN())));
}
