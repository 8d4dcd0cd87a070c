#pragma once
// Per-pixel hypothesis tests for jittered renderers (vri-verify --seeds): Welch's t-test of two means and
// the Benjamini-Hochberg procedure, which keeps the expected share of false discoveries among many
// pixels' tests at q (and the chance of any false discovery at q when no pixel differs).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vri {

// The regularised incomplete beta function I_x(a, b), for a, b > 0 and x in [0, 1] (DLMF 8.17.22's
// continued fraction, evaluated by the modified Lentz method; DLMF 8.17.4's symmetry where it converges
// faster). Throws vri::Error outside its domain.
double regularizedIncompleteBeta(double a, double b, double x);

// The two-sided p-value of Student's t statistic `t` with `df` > 0 degrees of freedom:
// P(|T| >= |t|) = I_{df / (df + t^2)}(df / 2, 1 / 2). An infinite t gives 0.
double studentTwoSidedP(double t, double df);

// Welch's test that two samples of `n` values each, with means ma, mb and unbiased variances va, vb, have
// equal expectations up to `margin` (|E_a - E_b| <= margin is no difference): the two-sided p-value of
// t = max(0, |ma - mb| - margin) / sqrt((va + vb) / n) on the Welch-Satterthwaite degrees of freedom.
// Where both variances are 0, the p-value is 0 when the means differ by more than the margin, else 1.
double welchP(double ma, double va, double mb, double vb, int n, double margin);

// A permutation test that two sets of n frames (each frame a list of values of the same length: an image's
// pixels and channels) come from one distribution: the statistic is D = sum over values of (mean_a - mean_b)^2;
// under the null hypothesis every split of the 2n frames into two sets of n is as likely as the observed one,
// so p = (1 + #{permuted D >= observed D}) / (1 + permutations). Exact for any distribution of the values and
// any dependence between them (whole frames are permuted). The permutations come from a fixed seed:
// the same frames give the same p on every machine.
double permutationP(const std::vector<const std::vector<float>*>& a, const std::vector<const std::vector<float>*>& b,
                    int permutations, std::uint64_t seed);

// How many of the hypotheses with these p-values the Benjamini-Hochberg procedure rejects at level q:
// the largest k with p_(k) <= k q / m, the p-values sorted ascending.
std::size_t benjaminiHochbergRejections(std::vector<double> p, double q);

}  // namespace vri
