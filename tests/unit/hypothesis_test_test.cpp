// The per-pixel tests of vri-verify --seeds: the incomplete beta function and Student's t against closed
// forms, Welch's test at its edges, and the Benjamini-Hochberg count.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "libvri/util/error.h"
#include "libvri/util/hypothesis_test.h"

using vri::studentTwoSidedP;

TEST_CASE("incomplete beta: closed forms") {
    for (const double x : {0.0, 0.1, 0.5, 0.93, 1.0}) {
        CHECK(vri::regularizedIncompleteBeta(1.0, 1.0, x) == doctest::Approx(x).epsilon(1e-14));
        CHECK(vri::regularizedIncompleteBeta(3.5, 1.0, x) == doctest::Approx(std::pow(x, 3.5)).epsilon(1e-13));
        CHECK(vri::regularizedIncompleteBeta(1.0, 2.0, x) == doctest::Approx(1.0 - (1.0 - x) * (1.0 - x)).epsilon(1e-13));
    }
    CHECK_THROWS_AS(vri::regularizedIncompleteBeta(0.0, 1.0, 0.5), vri::Error);
    CHECK_THROWS_AS(vri::regularizedIncompleteBeta(1.0, 1.0, 1.5), vri::Error);
}

TEST_CASE("Student's t: two-sided p-values against closed forms and tables") {
    // One degree of freedom is Cauchy's: p = 1 - 2 atan(|t|) / pi; two: p = 1 - |t| / sqrt(2 + t^2).
    for (const double t : {0.0, 0.3, 1.0, 4.0, 60.0}) {
        CHECK(studentTwoSidedP(t, 1.0) == doctest::Approx(1.0 - 2.0 * std::atan(t) / std::numbers::pi).epsilon(1e-12));
        CHECK(studentTwoSidedP(-t, 2.0) == doctest::Approx(1.0 - t / std::sqrt(2.0 + t * t)).epsilon(1e-12));
    }
    // The 0.975 quantiles of t(10) and t(30) (R's qt), and the normal's 1.959964 at a million.
    CHECK(studentTwoSidedP(2.228138851986273, 10.0) == doctest::Approx(0.05).epsilon(1e-10));
    CHECK(studentTwoSidedP(2.042272456301238, 30.0) == doctest::Approx(0.05).epsilon(1e-10));
    CHECK(studentTwoSidedP(1.959963984540054, 1e6) == doctest::Approx(0.05).epsilon(1e-5));
    CHECK(studentTwoSidedP(INFINITY, 5.0) == 0.0);
    CHECK(studentTwoSidedP(40.0, 15.0) < 1e-15);
}

TEST_CASE("Welch's test: equal samples, deterministic values and the margin") {
    CHECK(vri::welchP(0.5, 0.01, 0.5, 0.02, 16, 0.0) == 1.0);
    CHECK(vri::welchP(0.5, 0.0, 0.6, 0.0, 16, 0.0) == 0.0);      // no noise, different values
    CHECK(vri::welchP(0.5, 0.0, 0.6, 0.0, 16, 0.2) == 1.0);      // within the margin
    CHECK(vri::welchP(0.0, 0.0, 1e-7, 0.0, 16, 1e-6) == 1.0);
    // Equal variances: Welch's t is the pooled one, on 2 (n - 1) degrees of freedom.
    const double t = 0.1 / std::sqrt(2 * 0.04 / 16);
    CHECK(vri::welchP(0.6, 0.04, 0.5, 0.04, 16, 0.0) == doctest::Approx(studentTwoSidedP(t, 30.0)).epsilon(1e-12));
}

TEST_CASE("Benjamini-Hochberg: the largest k with p_(k) <= k q / m") {
    CHECK(vri::benjaminiHochbergRejections({0.01, 0.04, 0.03, 0.005}, 0.05) == 4);
    CHECK(vri::benjaminiHochbergRejections({0.01, 0.02, 0.5}, 0.05) == 2);
    CHECK(vri::benjaminiHochbergRejections({0.04, 0.5, 0.9}, 0.05) == 0);  // 0.04 > 0.05 / 3
    CHECK(vri::benjaminiHochbergRejections({}, 0.05) == 0);
}
