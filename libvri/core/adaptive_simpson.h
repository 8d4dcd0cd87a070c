#pragma once
// Paper B (Campagnolo, Celes, de Figueiredo, "Accurate Volume Rendering based on Adaptive Numerical
// Integration"): the iterative adaptive Simpson evaluation of the volume rendering integral along one
// ray, Algorithms 2 and 3, with the coupled and decoupled strategies. Uniform Simpson is the same
// code with h_min = h_max = h0: every try is then taken at once.
//
// The ray is parametrised by v in voxels (paper B's unit for h), v in [0, length]. The caller supplies
//   evaluate(v) -> RayPoint: extinction and emission per voxel of ray at v, and
//   knownEmpty(a, b) -> bool: true only when every point of [a, b] is known to give exactly zero
//                             (empty-space skipping: the points are then not evaluated, which
//                             changes neither a decision nor a bit of the result).
//
// Step control, as the paper states it:
//   - The inner integral (extinction) picks the step: try [t, t+h] with Simpson's rule on the whole
//     step (S) and on its two halves (D), error estimate E = |D - S| / 15; on failure halve h, on
//     success take the step and double h when the previous try also succeeded ("two successes in a
//     row"); h stays in [h_min, h_max]; at h_min the step is taken whatever E says.
//   - The tolerance moves with the step: eps(h) = eps * h / h0, which halves and doubles with h as
//     the paper's algorithms do, and stays consistent when h is clamped to h_max, h_min or the end of
//     the ray (the algorithms leave that case open).
//   - The outer integral (R, G, B and alpha in tandem, E the largest of the four) then covers the
//     inner step with its own Algorithm-2 loop. Coupled: it starts each interval with the inner step.
//     Decoupled: its step carries over from interval to interval, "at its own pace".
//   - An interval whose extinction (and emission) samples are all zero is skipped: nothing to add.
//   - Inside an outer step, transparency at the five points comes from the extinction samples of the
//     same points: Simpson on each half, and the integral of the quadratic through a half's three
//     points for the quarter points (exact for quadratics, one order below Simpson, no extra sample).
//
// The proposal for the next step is kept apart from the step actually tried, which may be shortened
// to end at the interval's or the ray's end: doubling the shortened step (as Algorithm 2 written
// literally would) would shrink the decoupled outer step at every inner interval.
//
// Accepted value: the Richardson form D + (D - S) / 15 by default, not the paper's D + E with
// E = |D - S| / 15. D - S estimates 15 times the error of D with its sign, so D + (D - S)/15 removes the
// leading error term (Boole's rule: exact for quintics); D + |D - S|/15 adds the estimate with the
// wrong sign wherever D < S and is then worse than D alone. The paper's form stays selectable so
// that the difference can be measured.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace vri {

enum class Coupling {
    Coupled,    // the outer integral starts every interval with the inner step
    Decoupled,  // the outer step is controlled on its own, the inner step only bounds its interval
};

enum class AcceptedValue {
    Richardson,  // D + (D - S) / 15
    PaperDPlusE, // D + |D - S| / 15, as paper B writes it
};
std::string_view acceptedValueName(AcceptedValue v);  // "richardson", "paper"
AcceptedValue parseAcceptedValue(std::string_view name, const std::string& what);

struct AdaptiveParameters {
    Coupling coupling = Coupling::Coupled;
    double tolerance = 0.01;  // eps at the step h0
    double h0 = 0.5;          // initial step, voxels
    double hMin = 0.1;        // voxels, > 0
    double hMax = 2.0;        // voxels; +infinity for no limit
    AcceptedValue accepted = AcceptedValue::Richardson;
};

// Throws vri::Error naming the parameter unless 0 < h_min <= h0 <= h_max and the tolerance is >= 0
// and finite. (h_max may be infinite.)
void validate(const AdaptiveParameters& p);

// Extinction kappa and emission e (per voxel of ray) at one point: I_c = ∫ e_c T dv, alpha = ∫ kappa T dv.
template <class Real>
struct RayPoint {
    Real kappa = 0, r = 0, g = 0, b = 0;
    bool zero() const { return kappa == Real(0) && r == Real(0) && g == Real(0) && b == Real(0); }
};

// One try of the step control, for the per-ray log (paper B Fig. 6).
struct AdaptiveTry {
    enum Kind : std::uint8_t { Inner, Outer };
    Kind kind;
    bool accepted;
    bool skipped;      // inner only: accepted with all samples zero, so no outer integral follows
    double t, h;       // the interval [t, t + h], voxels
    double error;      // E: |D - S| / 15, the largest channel's for the outer integral
    double tolerance;  // eps(h)
    // After an accepted outer try: the integrals so far and the transparency at t + h.
    double r, g, b, alpha, transparency;
};

struct AdaptiveCounts {
    std::uint64_t innerTries = 0, innerFailures = 0;
    std::uint64_t outerTries = 0, outerFailures = 0;
    std::uint64_t outerSteps = 0;        // accepted outer tries
    std::uint64_t acceptedAtMinimum = 0;  // tries taken at h_min with E above the tolerance
    std::uint64_t pointsUsed = 0;         // points the tries needed (each position once per try)
    std::uint64_t pointsEvaluated = 0;    // of those, evaluated: neither reused nor known empty

    AdaptiveCounts& operator+=(const AdaptiveCounts& o) {
        innerTries += o.innerTries;
        innerFailures += o.innerFailures;
        outerTries += o.outerTries;
        outerFailures += o.outerFailures;
        outerSteps += o.outerSteps;
        acceptedAtMinimum += o.acceptedAtMinimum;
        pointsUsed += o.pointsUsed;
        pointsEvaluated += o.pointsEvaluated;
        return *this;
    }
};

template <class Real>
struct AdaptiveResult {
    Real r = 0, g = 0, b = 0, alpha = 0;
    Real transparency = 1;
    bool terminated = false;  // ended by early termination before its length
    // The largest optical depth of an accepted step at its largest extinction, h max(kappa_k): tau h of
    // simpson_range.h, beyond whose limit one step may leave [0, 1].
    Real largestStepDepth = 0;
};

// The five points t + k h / 4 of one Simpson try, remembered so that the next try reuses what it
// shares with this one (halving keeps three, the next step keeps one, the coupled outer try keeps all).
template <class Real>
class SimpsonWindow {
public:
    template <class Evaluate, class KnownEmpty>
    void place(Real a, Real b, const Evaluate& evaluate, const KnownEmpty& knownEmpty, AdaptiveCounts& counts) {
        const Real h = b - a;
        Real x[5] = {a, a + h * Real(0.25), a + h * Real(0.5), a + h * Real(0.75), b};
        int reused[5];  // the previous window's point at the same position, or -1
        bool fresh = false;
        for (int k = 0; k < 5; ++k) {
            reused[k] = valid_ ? find(x[k]) : -1;
            fresh = fresh || reused[k] < 0;
        }
        // Asked only when a point must be evaluated: a try that reuses all five (the coupled outer
        // try) walks no bricks.
        const bool empty = fresh && knownEmpty(static_cast<double>(a), static_cast<double>(b));
        RayPoint<Real> next[5];
        for (int k = 0; k < 5; ++k) {
            if (reused[k] >= 0) {
                next[k] = p_[reused[k]];
            } else if (!empty) {
                next[k] = evaluate(x[k]);
                ++counts.pointsEvaluated;
            }  // else: known to be exactly zero, as RayPoint's default
        }
        counts.pointsUsed += 5;
        std::copy(x, x + 5, x_);
        std::copy(next, next + 5, p_);
        valid_ = true;
    }
    const RayPoint<Real>& operator[](int k) const { return p_[k]; }
    Real x(int k) const { return x_[k]; }

private:
    int find(Real x) const {
        for (int j = 0; j < 5; ++j)
            if (x_[j] == x) return j;
        return -1;
    }
    Real x_[5] = {};
    RayPoint<Real> p_[5];
    bool valid_ = false;
};

template <class Real>
class AdaptiveSimpsonRay {
public:
    AdaptiveSimpsonRay(const AdaptiveParameters& p, Real earlyTermination = 0)
        : p_(p), h0_(Real(p.h0)), hMin_(Real(p.hMin)), hMax_(static_cast<Real>(p.hMax)),
          epsPerVoxel_(Real(p.tolerance / p.h0)), earlyTermination_(earlyTermination) {}

    // Integrates v in [0, length]. `log`, when given, receives every try.
    template <class Evaluate, class KnownEmpty>
    AdaptiveResult<Real> integrate(Real length, const Evaluate& evaluate, const KnownEmpty& knownEmpty,
                                   AdaptiveCounts& counts, std::vector<AdaptiveTry>* log = nullptr) const {
        AdaptiveResult<Real> out;
        SimpsonWindow<Real> w;
        Control inner{std::min(h0_, hMax_)}, outer{std::min(h0_, hMax_)};
        Real t = 0;
        while (t < length && !(out.transparency < earlyTermination_)) {
            // Inner integral: find a step over which extinction is integrated within tolerance.
            Real end, h;
            for (;;) {
                h = std::min(inner.proposal, length - t);
                end = h == length - t ? length : t + h;
                w.place(t, end, evaluate, knownEmpty, counts);
                const Real d = half(w[0].kappa, w[1].kappa, w[2].kappa, h) + half(w[2].kappa, w[3].kappa, w[4].kappa, h);
                const Real s = h / 6 * (w[0].kappa + 4 * w[2].kappa + w[4].kappa);
                const Real e = std::abs(d - s) / 15;
                const bool ok = e <= tolerance(h) || h <= hMin_;
                ++counts.innerTries;
                if (ok && e > tolerance(h)) ++counts.acceptedAtMinimum;
                const bool skip = ok && allZero(w);
                if (log) log->push_back({AdaptiveTry::Inner, ok, skip, double(t), double(h), double(e), double(tolerance(h)),
                                         0, 0, 0, 0, 0});
                if (ok) {
                    inner.succeeded(hMax_);
                    if (skip) break;
                    if (p_.coupling == Coupling::Coupled) outer = Control{h};
                    integrateOuter(t, end, w, evaluate, knownEmpty, outer, out, counts, log);
                    break;
                }
                ++counts.innerFailures;
                inner.failed(h, hMin_);
            }
            t = end;
        }
        out.terminated = t < length;
        return out;
    }

private:
    // Step proposal and the "succeeded last time" flag of Algorithm 2.
    struct Control {
        explicit Control(Real h) : proposal(h) {}
        Real proposal;
        bool lastSucceeded = true;
        void succeeded(Real hMax) {  // the tried step was min(proposal, what was left)
            if (lastSucceeded) proposal = std::min(proposal * 2, hMax);
            lastSucceeded = true;
        }
        void failed(Real tried, Real hMin) {
            proposal = std::max(tried / 2, hMin);
            lastSucceeded = false;
        }
    };

    Real tolerance(Real h) const { return epsPerVoxel_ * h; }

    // Simpson's rule over one half [x0, x2] of a step of length h, from its three points.
    static Real half(Real f0, Real f1, Real f2, Real h) { return h / 12 * (f0 + 4 * f1 + f2); }
    // The integral over the first quarter [x0, x1] of the quadratic through a half's three points.
    static Real quarter(Real f0, Real f1, Real f2, Real h) { return h / 48 * (5 * f0 + 8 * f1 - f2); }

    Real accepted(Real d, Real s) const {
        return p_.accepted == AcceptedValue::Richardson ? d + (d - s) / 15 : d + std::abs(d - s) / 15;
    }

    static bool allZero(const SimpsonWindow<Real>& w) {
        for (int k = 0; k < 5; ++k)
            if (!w[k].zero()) return false;
        return true;
    }

    // Algorithm 2 on the four channels over [t, end], the transparency carried along.
    template <class Evaluate, class KnownEmpty>
    void integrateOuter(Real t, Real end, SimpsonWindow<Real>& w, const Evaluate& evaluate,
                        const KnownEmpty& knownEmpty, Control& control, AdaptiveResult<Real>& out,
                        AdaptiveCounts& counts, std::vector<AdaptiveTry>* log) const {
        while (t < end) {
            const Real h = std::min(control.proposal, end - t);
            const Real b = h == end - t ? end : t + h;
            w.place(t, b, evaluate, knownEmpty, counts);
            // Optical depth from t to each point, then the transparency there.
            const Real k0 = w[0].kappa, k1 = w[1].kappa, k2 = w[2].kappa, k3 = w[3].kappa, k4 = w[4].kappa;
            const Real depthHalf = half(k0, k1, k2, h);
            const Real depthD = depthHalf + half(k2, k3, k4, h);
            const Real depthS = h / 6 * (k0 + 4 * k2 + k4);
            const Real depth[5] = {0, quarter(k0, k1, k2, h), depthHalf, depthHalf + quarter(k2, k3, k4, h), depthD};
            Real f[4][5];  // channel x point: emission (or extinction, for alpha) times transparency
            for (int k = 0; k < 5; ++k) {
                const Real tr = out.transparency * std::exp(-depth[k]);
                f[0][k] = w[k].r * tr;
                f[1][k] = w[k].g * tr;
                f[2][k] = w[k].b * tr;
                f[3][k] = w[k].kappa * tr;
            }
            Real d[4], s[4], e = 0;
            for (int c = 0; c < 4; ++c) {
                d[c] = half(f[c][0], f[c][1], f[c][2], h) + half(f[c][2], f[c][3], f[c][4], h);
                s[c] = h / 6 * (f[c][0] + 4 * f[c][2] + f[c][4]);
                e = std::max(e, std::abs(d[c] - s[c]) / 15);
            }
            const bool ok = e <= tolerance(h) || h <= hMin_;
            ++counts.outerTries;
            if (ok) {
                if (e > tolerance(h)) ++counts.acceptedAtMinimum;
                ++counts.outerSteps;
                out.r += accepted(d[0], s[0]);
                out.g += accepted(d[1], s[1]);
                out.b += accepted(d[2], s[2]);
                out.alpha += accepted(d[3], s[3]);
                out.transparency *= std::exp(-accepted(depthD, depthS));
                out.largestStepDepth = std::max(out.largestStepDepth, h * std::max({k0, k1, k2, k3, k4}));
                control.succeeded(hMax_);
                t = b;
            } else {
                ++counts.outerFailures;
                control.failed(h, hMin_);
            }
            if (log)
                log->push_back({AdaptiveTry::Outer, ok, false, double(w.x(0)), double(h), double(e), double(tolerance(h)),
                                double(out.r), double(out.g), double(out.b), double(out.alpha), double(out.transparency)});
        }
    }

    AdaptiveParameters p_;
    Real h0_, hMin_, hMax_, epsPerVoxel_, earlyTermination_;
};

}  // namespace vri
