// The exact method's Gauss rules and their derivative bounds (gauss_error_bound.h): each rule integrates
// polynomials of degree 2n - 1 exactly, and on random sub-pieces (cubic colours and extinctions, either
// emission model) the error of every rule on every panel count stays below its bound.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include "vri/core/gauss_error_bound.h"

using namespace vri;

namespace {

using Cubic4 = std::array<double, 4>;

long double evaluate(const Cubic4& p, long double x) { return p[0] + x * (p[1] + x * (p[2] + x * p[3])); }

// D(x) = ell * integral_0^x tau.
long double depth(const Cubic4& tau, double ell, long double x) {
    return ell * x * (tau[0] + x * (tau[1] / 2 + x * (tau[2] / 3 + x * tau[3] / 4)));
}

long double integrand(const Cubic4& colour, const Cubic4& tau, bool timesTau, double ell, long double x) {
    const long double g = evaluate(colour, x) * (timesTau ? evaluate(tau, x) : 1.0L);
    return ell * g * std::exp(-depth(tau, ell, x));
}

// The n-point rule on k equal panels of [0, 1], in long double so that only the rule's error remains.
long double gauss(int n, int k, const Cubic4& colour, const Cubic4& tau, bool timesTau, double ell) {
    const GaussRule& rule = gaussRule(n);
    long double sum = 0.0L;
    for (int p = 0; p < k; ++p)
        for (int i = 0; i < n; ++i) {
            const long double x = (p + static_cast<long double>(rule.node[i])) / k;
            sum += rule.weight[i] * integrand(colour, tau, timesTau, ell, x);
        }
    return sum / k;
}

}  // namespace

TEST_CASE("gauss rules: n points integrate degree 2n - 1 exactly") {
    for (int n = 1; n <= 3; ++n) {
        const GaussRule& rule = gaussRule(n);
        CHECK(rule.n == n);
        for (int degree = 0; degree < 2 * n; ++degree) {
            double sum = 0.0;
            for (int i = 0; i < n; ++i) sum += rule.weight[i] * std::pow(rule.node[i], degree);
            CHECK(sum == doctest::Approx(1.0 / (degree + 1)).epsilon(1e-15));
        }
        double sum = 0.0;  // and not degree 2n: the remainder is not zero
        for (int i = 0; i < n; ++i) sum += rule.weight[i] * std::pow(rule.node[i], 2 * n);
        CHECK(std::abs(sum - 1.0 / (2 * n + 1)) > 1e-6);
    }
}

TEST_CASE("gauss error bound: every rule's error on random sub-pieces is below its bound") {
    std::mt19937 rng(15);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), length(0.05, 3.0);
    int tight = 0, cases = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const bool timesTau = trial % 2 == 0;
        const double ell = length(rng);
        // Extinction >= 0 on [0, 1] (as the TF's is): a random cubic lifted above its sampled minimum.
        Cubic4 tau{unit(rng), unit(rng), 0.5 * unit(rng), 0.25 * unit(rng)};
        double lowest = 1e300;
        for (int i = 0; i <= 1000; ++i) lowest = std::min(lowest, static_cast<double>(evaluate(tau, i / 1000.0L)));
        tau[0] += std::abs(lowest) + 0.01;
        Cubic4 colour[3];
        for (auto& c : colour) c = {unit(rng), unit(rng), 0.5 * unit(rng), 0.25 * unit(rng)};
        const std::array<double, 3> bound = gaussErrorBounds(colour, tau, timesTau, ell, 1.0);
        for (const auto& c : colour) {
            // The exact integral: the 3-point rule on 4096 panels, whose error is below 1e-25 here.
            const long double exact = gauss(3, 4096, c, tau, timesTau, ell);
            for (int n = 1; n <= 3; ++n)
                for (int k = 1; k <= 4; ++k) {
                    CAPTURE(trial);
                    CAPTURE(n);
                    CAPTURE(k);
                    const double error = static_cast<double>(std::abs(gauss(n, k, c, tau, timesTau, ell) - exact));
                    const double allowed = ell * bound[n - 1] / std::pow(k, 2 * n);
                    CHECK(error <= allowed + 1e-18);
                    ++cases;
                    if (error > 0.01 * allowed) ++tight;
                }
        }
    }
    // The bounds are not vacuous: a good share of the errors come within a factor 100 of them.
    CHECK(tight > cases / 20);
}
