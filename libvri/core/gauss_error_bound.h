#pragma once
// A rigorous bound on the error of n-point Gauss-Legendre quadrature (n = 1, 2, 3) of
//     f(lambda) = g(lambda) exp(-D(lambda)),  lambda in [0, 1],
// the exact method's integrand on one transfer-function sub-piece (exact_ray.cpp): g is the emission
// (C tau or C, products of cubics), D the optical depth, a quartic with D' = ell tau >= 0 and D(0) = 0.
// The classical remainder of the n-point rule on [0, 1] is f^(2n)(xi) (n!)^4 / ((2n + 1) ((2n)!)^3)
// (Davis and Rabinowitz, Methods of Numerical Integration, 2.7.12), so a bound on |f^(2n)| over
// [0, 1] bounds the error, unlike the Gauss-Kronrod estimate |K - G|, which only estimates it. On k
// equal panels each remainder scales by k^-(2n + 1): k^-2n in all.
//
// The derivative bounds come from the coefficients: on [0, 1], |p^(j)| <= sum_i |p_i| i! / (i - j)!;
// Leibniz's rule gives those of C tau; exp(-D)^(m) = exp(-D) Y_m(-D', -D'', ...) with Y_m the
// complete Bell polynomial, whose coefficients are positive, so |exp(-D)^(m)| <= E_max Y_m(|D'|,
// |D''|, ...) where E_max bounds exp(-D) (1 up to the rounding of D).
#include <array>

namespace vri {

// The bounds on |f^(2n)| over [0, 1] for n = 1, 2, 3, times each rule's remainder constant: the
// error of n-point Gauss on k panels of [0, 1] is at most bound[n - 1] / k^(2n), in each of the three
// colour channels (one bound for all: the largest channel's derivative bounds). `colour` and `tau`
// are cubics in lambda; g = colour tau when `colourTimesExtinction`, else g = colour; ell the length
// that turns tau into D' (D = ell times the integral of tau); `transparencyMax` bounds exp(-D) on [0, 1].
std::array<double, 3> gaussErrorBounds(const std::array<double, 4> (&colour)[3], const std::array<double, 4>& tau,
                                       bool colourTimesExtinction, double ell, double transparencyMax);

// The n-point Gauss-Legendre rule (n = 1, 2, 3) on [0, 1]: nodes and weights (summing to 1).
struct GaussRule {
    int n;
    double node[3], weight[3];
};
const GaussRule& gaussRule(int n);

}  // namespace vri
