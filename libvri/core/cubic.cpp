#include "libvri/core/cubic.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vri {

Cubic Cubic::reparameterised(double x0, double h) const {
    // Taylor coefficients at x0, each scaled by h^k.
    const double d1 = c[1] + x0 * (2.0 * c[2] + x0 * (3.0 * c[3]));
    const double d2 = c[2] + x0 * (3.0 * c[3]);
    return {{(*this)(x0), d1 * h, d2 * h * h, c[3] * h * h * h}};
}

int criticalPoints(const Cubic& p, double lo, double hi, double out[2]) {
    // p'(x) = a x^2 + b x + c; the quadratic is solved without cancellation.
    const double a = 3.0 * p.c[3], b = 2.0 * p.c[2], c = p.c[1];
    double roots[2];
    int n = 0;
    if (a == 0.0) {
        if (b != 0.0) roots[n++] = -c / b;
    } else {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            roots[n++] = q / a;
            if (q != 0.0) roots[n++] = c / q;
        }
    }
    int kept = 0;
    for (int i = 0; i < n; ++i)
        if (roots[i] > lo && roots[i] < hi) out[kept++] = roots[i];
    if (kept == 2) {
        if (out[0] > out[1]) std::swap(out[0], out[1]);
        if (out[0] == out[1]) kept = 1;
    }
    return kept;
}

double solveMonotone(const Cubic& p, double level, double lo, double hi, RootStart start) {
    const double fLo = p(lo) - level, fHi = p(hi) - level;
    if (fLo == 0.0) return lo;
    if (fHi == 0.0) return hi;
    const bool rising = fLo < 0.0;  // the sign of f = p - level below the root
    double x = 0.5 * (lo + hi), best = std::abs(fLo) <= std::abs(fHi) ? lo : hi;
    if (start == RootStart::Chord) {
        const double chord = lo + (hi - lo) * (fLo / (fLo - fHi));  // fLo and fHi differ in sign
        if (chord > lo && chord < hi) x = chord;
    }
    double bestF = std::min(std::abs(fLo), std::abs(fHi));
    double lastStep = hi - lo;
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double f = p(x) - level;
        if (f == 0.0) return x;
        if (std::abs(f) < bestF) best = x, bestF = std::abs(f);
        if ((f < 0.0) == rising)
            lo = x;
        else
            hi = x;
        // Newton while it stays inside the bracket and its steps at least halve (as in Numerical
        // Recipes' rtsafe); bisection otherwise, so the bracket always shrinks.
        const double slope = p.derivative(x);
        double next = slope != 0.0 ? x - f / slope : lo;
        if (!(next > lo && next < hi) || std::abs(next - x) > 0.5 * lastStep) next = 0.5 * (lo + hi);
        if (next == x || !(next > lo && next < hi)) break;  // below the spacing of doubles
        lastStep = std::abs(next - x);
        x = next;
    }
    return best;
}

}  // namespace vri
