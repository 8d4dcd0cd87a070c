#include "libvri/util/hypothesis_test.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libvri/util/error.h"

namespace vri {

namespace {

// The continued fraction of I_x(a, b) (DLMF 8.17.22), 1 / (1 + d1 / (1 + d2 / (1 + ...))), by modified
// Lentz: it converges fast for x < (a + 1) / (a + b + 2).
double betaContinuedFraction(double a, double b, double x) {
    constexpr double tiny = 1e-300, eps = 1e-15;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    if (std::abs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double f = d;
    for (int m = 1; m <= 10000; ++m) {
        // d_{2m}: the even term, then d_{2m+1}: the odd one.
        for (const double term : {m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
                                  -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0))}) {
            d = 1.0 + term * d;
            if (std::abs(d) < tiny) d = tiny;
            c = 1.0 + term / c;
            if (std::abs(c) < tiny) c = tiny;
            d = 1.0 / d;
            f *= c * d;
        }
        if (std::abs(c * d - 1.0) < eps) return f;
    }
    return f;  // 10,000 rounds: far more than a t-test's arguments need
}

}  // namespace

double regularizedIncompleteBeta(double a, double b, double x) {
    if (!(a > 0.0) || !(b > 0.0) || !(x >= 0.0 && x <= 1.0))
        throw Error("the incomplete beta function needs a, b > 0 and x in [0, 1]");
    if (x == 0.0 || x == 1.0) return x;
    const double logFront = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(logFront) * betaContinuedFraction(a, b, x) / a;
    return 1.0 - std::exp(logFront) * betaContinuedFraction(b, a, 1.0 - x) / b;  // I_x(a, b) = 1 - I_{1-x}(b, a)
}

double studentTwoSidedP(double t, double df) {
    if (!(df > 0.0) || std::isnan(t)) throw Error("Student's t needs a number and degrees of freedom > 0");
    if (std::isinf(t)) return 0.0;
    return regularizedIncompleteBeta(df / 2.0, 0.5, df / (df + t * t));
}

double welchP(double ma, double va, double mb, double vb, int n, double margin) {
    const double excess = std::max(0.0, std::abs(ma - mb) - margin);
    const double sa = va / n, sb = vb / n;
    if (sa + sb == 0.0) return excess > 0.0 ? 0.0 : 1.0;
    // Welch-Satterthwaite: (sa + sb)^2 / (sa^2 / (n - 1) + sb^2 / (n - 1)).
    const double df = (sa + sb) * (sa + sb) * (n - 1) / (sa * sa + sb * sb);
    return studentTwoSidedP(excess / std::sqrt(sa + sb), df);
}

double permutationP(const std::vector<const std::vector<float>*>& a, const std::vector<const std::vector<float>*>& b,
                    int permutations, std::uint64_t seed) {
    const std::size_t n = a.size();
    if (n == 0 || b.size() != n || permutations < 1) throw Error("a permutation test needs two sets of n > 0 frames");
    std::vector<const std::vector<float>*> frames(a.begin(), a.end());
    frames.insert(frames.end(), b.begin(), b.end());
    const std::size_t m = frames.front()->size();
    for (const std::vector<float>* f : frames)
        if (f->size() != m) throw Error("a permutation test's frames differ in size");
    std::vector<double> total(m, 0.0);
    for (const std::vector<float>* f : frames)
        for (std::size_t i = 0; i < m; ++i) total[i] += (*f)[i];
    // D from the sum over set a: mean_a - mean_b = (2 sum_a - total) / n.
    std::vector<double> sumA(m);
    const auto statistic = [&](const std::vector<std::size_t>& order) {
        std::fill(sumA.begin(), sumA.end(), 0.0);
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t i = 0; i < m; ++i) sumA[i] += (*frames[order[k]])[i];
        double d = 0.0;
        for (std::size_t i = 0; i < m; ++i) {
            const double diff = (2.0 * sumA[i] - total[i]) / static_cast<double>(n);
            d += diff * diff;
        }
        return d;
    };
    std::vector<std::size_t> order(2 * n);
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    const double observed = statistic(order);
    // SplitMix64 (Steele, Lea and Flood): a generator fully specified here, unlike the standard library's
    // distributions, so that the permutations are the same everywhere.
    std::uint64_t state = seed;
    const auto next = [&] {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    int asLarge = 0;
    for (int r = 0; r < permutations; ++r) {
        for (std::size_t k = 0; k < n; ++k)  // the first n of a Fisher-Yates shuffle: a random set a
            std::swap(order[k], order[k + next() % (order.size() - k)]);
        // A split scores like the observed one within rounding when it is the observed one (or its mirror).
        if (statistic(order) >= observed * (1.0 - 1e-12)) ++asLarge;
    }
    return (1.0 + asLarge) / (1.0 + permutations);
}

std::size_t benjaminiHochbergRejections(std::vector<double> p, double q) {
    std::sort(p.begin(), p.end());
    const double m = static_cast<double>(p.size());
    std::size_t rejected = 0;
    for (std::size_t k = 1; k <= p.size(); ++k)
        if (p[k - 1] <= static_cast<double>(k) * q / m) rejected = k;
    return rejected;
}

}  // namespace vri
