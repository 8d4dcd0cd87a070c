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

// Where solveMonotone takes its first iterate: the bracket's midpoint (the references' bits), or where
// the chord through (lo, p(lo)) and (hi, p(hi)) meets the level, which on a nearly linear piece of a
// cell leaves Newton a step or two.
enum class RootStart { Midpoint, Chord };

// The x in [lo, hi] with p(x) = level, for p monotone on [lo, hi] with the level between p(lo) and
// p(hi): safeguarded Newton (bisection whenever Newton leaves the bracket or converges slowly) down
// to neighbouring doubles, so the root is as exact as double arithmetic can tell.
double solveMonotone(const Cubic& p, double level, double lo, double hi, RootStart start = RootStart::Midpoint);

// The trilinear interpolant of a cell's corner values along the segment from cell coordinates w0 to
// w1 (each in [0, 1]^3) as a cubic in sigma in [0, 1]. Corner (dx, dy, dz) is corners[dx + 2 dy + 4 dz].
// The coefficients come from the corners and the linear weights, exactly up to rounding: the
// interpolant is a product of three linear weights, so nothing is fitted. Inline: the walk consumes the
// coefficients in registers, where a call returned them through memory that the caller read back as
// pairs, each read stalled on the two stores it spans.
inline Cubic trilinearAlongSegment(const std::array<double, 8>& v, const glm::dvec3& w0, const glm::dvec3& w1) {
    // Each weight is linear, w(sigma) = w0 + (w1 - w0) sigma; one lerp per axis raises the degree by one.
    using Poly = std::array<double, 4>;
    auto lerp = [](const Poly& a, const Poly& b, double w, double dw) {
        Poly r{};
        for (int k = 0; k < 4; ++k) {
            const double d = b[k] - a[k];
            r[k] += a[k] + w * d;
            if (k + 1 < 4) r[k + 1] += dw * d;
        }
        return r;
    };
    const glm::dvec3 dw = w1 - w0;
    Poly x[4], y[2];
    for (int i = 0; i < 4; ++i) x[i] = lerp({v[2 * i]}, {v[2 * i + 1]}, w0.x, dw.x);  // (dy, dz) = (i & 1, i >> 1)
    for (int i = 0; i < 2; ++i) y[i] = lerp(x[2 * i], x[2 * i + 1], w0.y, dw.y);
    return {lerp(y[0], y[1], w0.z, dw.z)};
}

}  // namespace vri
