#pragma once
// Early ray termination, shared by the scalar loop (cpu_renderer.cpp) and the packet engine (simd_march.cpp),
// which must end every ray at the same sample. Either form stops a ray once its transparency T falls
// below a threshold; `--early-termination auto` chooses the threshold per ray so that the samples left
// out could change no channel by more than RenderOptions::terminationBound:
//  - alpha: the rest multiplies T by a factor in [0, 1], so alpha moves by at most T.
//  - colour, g = C tau, composite: sample k adds C_k (T_k - T_k+1), at most C_max (T - T_end) <= C_max T.
//  - colour, g = C tau, Riemann: sample k adds C_k T_k x_k with x_k = tau_k dx, and T_k x_k =
//    (T_k - T_k+1) x_k / (1 - exp(-x_k)); that factor grows with x, so the rest adds at most
//    C_max T F with F = x_max / (1 - exp(-x_max)), x_max = tau_max dx (F = 1 as tau_max dx -> 0).
//  - colour, g = C (either integrator): sample k adds at most C_k T_k dx (composite's
//    (1 - exp(-tau dx)) / tau <= dx), so the rest adds at most C_max T times the ray's length.
// So the rest changes a channel by at most K T with K = max(1, C_max F) or max(1, C_max length), and the
// ray ends once T < bound / K. These bound the sums of the samples left out, as the integrator would
// have computed them, up to the rounding of those additions. The Simpson methods take the bound of the
// integral itself (g = C tau: C_max T; g = C: C_max T times the longest ray through the box).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "libvri/core/cpu_renderer.h"

namespace vri {

class TerminationRule {
public:
    TerminationRule(const TransferFunction& tf, const RenderOptions& opt, double longestRay)
        : integrator_(opt.integrator), emission_(tf.emission()), transparency_(opt.earlyTermination),
          bound_(opt.terminationBound), longestRay_(longestRay) {
        for (const TransferFunctionPoint& p : tf.points()) {
            maxColour_ = std::max({maxColour_, p.r, p.g, p.b});
            maxTau_ = std::max(maxTau_, p.tau);
        }
    }

    bool enabled() const { return transparency_ > 0.0 || bound_ > 0.0; }

    // The transparency below which a ray of `count` samples, each `dx` world units long, ends (0: never),
    // rounded down to Real so that the comparison in Real keeps the bound.
    template <class Real>
    Real threshold(double dx, std::int64_t count) const {
        if (!(bound_ > 0.0)) return static_cast<Real>(transparency_);
        const double t = bound_ / factor(dx, count);
        Real r = static_cast<Real>(t);
        if (static_cast<double>(r) > t) r = std::nextafter(r, Real(0));
        return r;
    }

    // What the samples after the one that left the ray at `transparency` could have added to any channel.
    double leftOut(double transparency, double dx, std::int64_t count) const {
        return transparency * factor(dx, count);
    }

    // The same for the Simpson methods, which integrate in steps of their own: one threshold per render.
    double simpsonThreshold() const {
        if (!(bound_ > 0.0)) return transparency_;
        return bound_ / simpsonFactor();
    }
    double simpsonLeftOut(double transparency) const { return transparency * simpsonFactor(); }

private:
    // K: the most the rest of a ray can add to a channel per unit of transparency (see above).
    double factor(double dx, std::int64_t count) const {
        if (emission_ == EmissionModel::Colour)
            return std::max(1.0, maxColour_ * dx * static_cast<double>(count));
        if (integrator_ == Integrator::Composite) return std::max(1.0, maxColour_);
        const double x = maxTau_ * dx;
        return std::max(1.0, maxColour_ * (x > 0.0 ? x / -std::expm1(-x) : 1.0));
    }
    double simpsonFactor() const {
        return std::max(1.0, emission_ == EmissionModel::Colour ? maxColour_ * longestRay_ : maxColour_);
    }

    Integrator integrator_;
    EmissionModel emission_;
    double transparency_, bound_, longestRay_;
    double maxColour_ = 0.0, maxTau_ = 0.0;
};

}  // namespace vri
