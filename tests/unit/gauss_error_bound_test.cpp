// The exact method's Gauss rules and their derivative bounds (gauss_error_bound.h): each rule integrates
// polynomials of degree 2n - 1 exactly, and on random sub-pieces (cubic colours and extinctions, either
// emission model) the error of every rule on every panel count stays below its bound.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>

#include "libvri/core/gauss_error_bound.h"

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

TEST_CASE("gauss error bound: the written-out sums are the loops over Pascal's triangle, bit for bit") {
    // The bound as the general formulas read, summed in the same order: Leibniz's rule for g = C tau,
    // the Bell recurrence for exp(-D), the sum for |f^(2n)|. A term left out or mistyped in
    // gaussErrorBounds' written-out sums changes its bits on some of these inputs.
    auto loops = [](const Cubic4 (&colour)[3], const Cubic4& tau, bool timesTau, double ell, double tMax) {
        auto derivatives = [](const Cubic4& p) {
            const double a1 = std::abs(p[1]), a2 = std::abs(p[2]), a3 = std::abs(p[3]);
            return std::array<double, 7>{std::abs(p[0]) + a1 + a2 + a3, a1 + 2.0 * a2 + 3.0 * a3, 2.0 * a2 + 6.0 * a3,
                                         6.0 * a3, 0.0, 0.0, 0.0};
        };
        double binomial[7][7] = {};
        for (int m = 0; m < 7; ++m) {
            binomial[m][0] = 1.0;
            for (int i = 1; i <= m; ++i) binomial[m][i] = binomial[m - 1][i - 1] + (i < m ? binomial[m - 1][i] : 0.0);
        }
        std::array<double, 7> c = derivatives(colour[0]);
        for (int k = 1; k < 3; ++k) {
            const std::array<double, 7> other = derivatives(colour[k]);
            for (int j = 0; j < 4; ++j) c[j] = std::max(c[j], other[j]);
        }
        const std::array<double, 7> t = derivatives(tau);
        std::array<double, 7> g = c, y{};
        if (timesTau)
            for (int m = 0; m < 7; ++m) {
                double r = 0.0;
                for (int i = std::max(0, m - 3); i <= std::min(m, 3); ++i) r += binomial[m][i] * c[i] * t[m - i];
                g[m] = r;
            }
        y[0] = 1.0;
        for (int m = 0; m < 6; ++m) {
            double r = 0.0;
            for (int i = 0; i <= std::min(m, 3); ++i) r += binomial[m][i] * (ell * t[i]) * y[m - i];
            y[m + 1] = r;
        }
        const double remainder[3] = {1.0 / 24.0, 1.0 / 4320.0, 1.0 / 2016000.0};
        std::array<double, 3> bound{};
        for (int n = 1; n <= 3; ++n) {
            double r = 0.0;
            for (int k = 0; k <= 2 * n; ++k) r += binomial[2 * n][k] * g[k] * y[2 * n - k];
            bound[n - 1] = tMax * r * remainder[n - 1];
        }
        return bound;
    };
    std::mt19937 rng(16);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-8.0, 8.0);
    for (int trial = 0; trial < 2000; ++trial) {
        CAPTURE(trial);
        auto cubic = [&] {
            const double scale = std::pow(10.0, exponent(rng));
            return Cubic4{scale * unit(rng), scale * unit(rng), scale * unit(rng), scale * unit(rng)};
        };
        const Cubic4 colour[3] = {cubic(), cubic(), cubic()}, tau = cubic();
        const double ell = std::pow(10.0, exponent(rng)), tMax = 1.0 + std::abs(unit(rng));
        for (bool timesTau : {true, false}) {
            const std::array<double, 3> expected = loops(colour, tau, timesTau, ell, tMax);
            const std::array<double, 3> bound = gaussErrorBounds(colour, tau, timesTau, ell, tMax);
            for (int n = 0; n < 3; ++n) CHECK(bound[n] == expected[n]);
        }
    }
}
