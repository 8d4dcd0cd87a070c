#pragma once
// Cubic polynomials on [0, 1]: the form the trilinear interpolant takes along a straight line inside
// one cell, which the exact reference (exact_reference.h) splits and integrates piece by piece.
#include <array>

#include <glm/vec3.hpp>

namespace vri {

struct Cubic {
    std::array<double, 4> c{};  // c[0] + c[1] x + c[2] x^2 + c[3] x^3

    double operator()(double x) const { return c[0] + x * (c[1] + x * (c[2] + x * c[3])); }
    double derivative(double x) const { return c[1] + x * (2.0 * c[2] + x * (3.0 * c[3])); }
    // p(x0 + h y) as a cubic in y (a Taylor shift and a scaling): a sub-interval of a piece becomes
    // [0, 1] again, so that every polynomial is evaluated where it is well conditioned.
    Cubic reparameterised(double x0, double h) const;
};

// The points in (lo, hi) where the derivative vanishes, in increasing order; returns their count
// (0, 1 or 2). Between consecutive ones (and lo, hi) the cubic is monotone.
int criticalPoints(const Cubic& p, double lo, double hi, double out[2]);

// The x in [lo, hi] with p(x) = level, for p monotone on [lo, hi] with the level between p(lo) and
// p(hi): safeguarded Newton (bisection whenever Newton leaves the bracket or converges slowly) down
// to neighbouring doubles, so the root is as exact as double arithmetic can tell.
double solveMonotone(const Cubic& p, double level, double lo, double hi);

// The trilinear interpolant of a cell's corner values along the segment from cell coordinates w0 to
// w1 (each in [0, 1]^3) as a cubic in sigma in [0, 1]. Corner (dx, dy, dz) is corners[dx + 2 dy + 4 dz].
// The coefficients come from the corners and the linear weights, exactly up to rounding: the
// interpolant is a product of three linear weights, so nothing is fitted.
Cubic trilinearAlongSegment(const std::array<double, 8>& corners, const glm::dvec3& w0, const glm::dvec3& w1);

}  // namespace vri
