#pragma once
// Early ray termination, shared by the scalar loop (cpu_renderer.cpp) and the packet engine (simd_march.cpp),
// which must end every ray at the same sample. Either form stops a ray once its transparency T falls
// below a threshold; `--early-termination auto` chooses the threshold per ray so that the samples left
// out could change no channel by more than RenderOptions::terminationBound:
//  - alpha: the rest multiplies T by a factor in [0, 1], so alpha moves by at most T.
//  - colour, g = C tau, composite: sample k adds C_k (T_k - T_k+1), at most C_max (T - T_end) <= C_max T.
//  - colour, g = C tau, Riemann: sample k adds C_k T_k x_k with x_k = tau_k dx, and T_k x_k =
//    (T_k - T_k+1) x_k / (1 - exp(-x_k)); that factor grows with x, so the rest adds at most
//    C_max T G(x_max) with G(x) = x / (1 - exp(-x)), x_max = tau_max dx (G = 1 as x -> 0).
//  - colour, g = C (either integrator): sample k adds at most C_k T_k dx (composite's
//    (1 - exp(-tau dx)) / tau <= dx), so the rest adds at most C_max T times the ray's length.
// So the rest changes a channel by at most K T with K = max(1, C_max G) or max(1, C_max length), and the
// ray ends once T < bound / K. These bound the sums of the samples left out, as the integrator would
// have computed them, up to the rounding of those additions.
//
// The Simpson methods (adaptive_simpson.h) add, per accepted step of h voxels, a quadrature of the four
// channels f = e T over the five points t + k h / 4, not the integral: a bound of the integral (C_max T)
// is no bound of what they add, and on Bonsai the rest they left out reached 6.5 times it. Per step:
//  - the weights are positive and sum to h: Richardson's D + (D - S) / 15 is Boole's rule,
//    h / 180 (14, 64, 24, 64, 14); paper B's D + |D - S| / 15 is Boole's where D >= S and
//    h / 180 (16, 56, 36, 56, 16) where D < S. The step's optical depth D_i takes the same form, with its
//    own sign of D - S, so a channel's weights are at most W times the depth's at every point: W = 1
//    (Richardson), 36 / 24 = 1.5 (paper).
//  - T_k = T_i exp(-depth_k) with depth_k from the quadratic through a half's three points: at the
//    quarter points h / 48 (5 k_0 + 8 k_1 - k_2) >= -h kappa_max / 48, elsewhere >= 0, so
//    T_k <= T_i M with M = exp(h kappa_max / 48); the step ends at T_i+1 = T_i exp(-D_i) <= T_i.
//  - g = C tau (e = C kappa): step i adds at most C_max M W T_i D_i, and T_i D_i = (T_i - T_i+1) D_i /
//    (1 - exp(-D_i)) <= G(x) (T_i - T_i+1), the Riemann factor above with x = kappa_max h >= D_i: the rest
//    adds at most C_max M W G(x) T. Alpha (e = kappa) is the same with C_max = 1.
//  - g = C (e = C per voxel of ray): step i adds at most C_max M T_i times its world length, the rest at
//    most C_max M T times the longest ray; alpha as for g = C tau.
// h is at most h_max (the step of uniform Simpson) and never more than the longest ray, kappa_max = tau_max
// times the largest world length of a voxel of ray. Steps without an h_max make M and G grow with the
// whole ray, so that K may leave double's range: no ray could then end, and the render refuses `auto`.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "libvri/core/box.h"
#include "libvri/core/render_contract.h"

namespace vri {

class TerminationRule {
public:
    // `box` and `dims`: the scene's (Scene::box(), Scene::dims()), which bound a ray's length and the
    // world length of a voxel of ray.
    TerminationRule(const TransferFunction& tf, const RenderOptions& opt, const Box& box, const glm::dvec3& dims)
        : integrator_(opt.integrator), emission_(tf.emission()), transparency_(opt.earlyTermination),
          bound_(opt.terminationBound), longestRay_(glm::length(box.size())) {
        const TransferFunctionSample<double> top = tf.largest();
        maxColour_ = std::max({top.r, top.g, top.b});
        maxTau_ = top.tau;
        if (isSimpson(integrator_)) {
            const glm::dvec3 worldPerVoxel = box.size() / dims;
            const double kappaMax = maxTau_ * std::max({worldPerVoxel.x, worldPerVoxel.y, worldPerVoxel.z});
            const AdaptiveParameters p = simpsonParameters(opt);
            const double depth = kappaMax * std::min(p.hMax, glm::length(dims));  // x: a step's largest depth
            const double overshoot = std::exp(depth / 48.0);                       // M
            const double weights = p.accepted == AcceptedValue::Richardson ? 1.0 : 1.5;  // W
            const double alpha = overshoot * weights * depthFactor(depth);
            simpsonFactor_ = emission_ == EmissionModel::Colour
                                 ? std::max(alpha, maxColour_ * overshoot * longestRay_)
                                 : std::max(1.0, maxColour_) * alpha;
        }
    }

    bool enabled() const { return transparency_ > 0.0 || bound_ > 0.0; }

    // The transparency below which a ray of `count` samples, each `dx` world units long, ends (0: never),
    // rounded down to Real so that the comparison in Real keeps the bound.
    template <class Real>
    Real threshold(double dx, std::int64_t count) const {
        if (!(bound_ > 0.0)) return static_cast<Real>(transparency_);
        return roundedDown<Real>(bound_ / factor(dx, count));
    }

    // What the samples after the one that left the ray at `transparency` could have added to any channel.
    double leftOut(double transparency, double dx, std::int64_t count) const {
        return transparency * factor(dx, count);
    }

    // The same for the Simpson methods, which integrate in steps of their own: one threshold per render,
    // 0 (no ray ends) where K left double's range.
    template <class Real>
    Real simpsonThreshold() const {
        if (!(bound_ > 0.0)) return static_cast<Real>(transparency_);
        return roundedDown<Real>(bound_ / simpsonFactor_);
    }
    double simpsonLeftOut(double transparency) const { return transparency * simpsonFactor_; }
    double simpsonFactor() const { return simpsonFactor_; }

private:
    // G(x) = x / (1 - exp(-x)): what a quadrature that weighs T_i tau h may add per unit of transparency
    // it takes away (see above).
    static double depthFactor(double x) { return x > 0.0 ? x / -std::expm1(-x) : 1.0; }

    template <class Real>
    static Real roundedDown(double t) {
        Real r = static_cast<Real>(t);
        if (static_cast<double>(r) > t) r = std::nextafter(r, Real(0));
        return r;
    }

    // K: the most the rest of a ray can add to a channel per unit of transparency (see above).
    double factor(double dx, std::int64_t count) const {
        if (emission_ == EmissionModel::Colour)
            return std::max(1.0, maxColour_ * dx * static_cast<double>(count));
        if (integrator_ == Integrator::Composite) return std::max(1.0, maxColour_);
        return std::max(1.0, maxColour_ * depthFactor(maxTau_ * dx));
    }

    Integrator integrator_;
    EmissionModel emission_;
    double transparency_, bound_, longestRay_;
    double maxColour_ = 0.0, maxTau_ = 0.0;
    double simpsonFactor_ = 1.0;  // K of the Simpson methods
};

}  // namespace vri
