#pragma once
// Front-to-back accumulation of the emission-absorption integral from point samples.
#include <cmath>
#include <string>
#include <string_view>

#include "libvri/core/float_exp.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/core/transfer_function.h"

namespace vri {

// The exponentials of the fixed-step integrators: the C library's in double; in float the shared
// polynomial of float_exp.h, which the packet engine (simd_march.h) evaluates lane by lane alike.
inline double exponential(double x) { return std::exp(x); }
inline float exponential(float x) { return expFloat(x); }
inline double exponentialMinusOne(double x) { return std::expm1(x); }
inline float exponentialMinusOne(float x) { return expm1Float(x); }

enum class Integrator {
    // Paper A eq. (5)/(6): I = sum_i g_i dx prod_{j<i} exp(-tau_j dx), the Riemann sum of the
    // outer integral with the inner one summed over the samples before i.
    Riemann,
    // Opacity-corrected compositing: each sample stands for a segment of constant scalar, integrated
    // exactly: I += T g (1 - exp(-tau dx)) / tau, which is C alpha with alpha = 1 - exp(-tau dx)
    // when g = C tau.
    Composite,
    // Simpson's rule on uniform steps h (each split into two Simpson panels, samples h / 4 apart):
    // paper B's adaptive code with h_min = h_max = h0 = h, so every try is taken.
    Simpson,
    // Paper B's iterative adaptive Simpson, Algorithm 3, coupled and decoupled (adaptive_simpson.h).
    Coupled,
    Decoupled,
    // Pre-integrated classification (preintegration_table.h): each sample stands for the segment of the
    // ray it is the midpoint of, as in composite, integrated by a table lookup of the scalars at the
    // segment's ends (order 2: and the sample's own, the midpoint).
    Preintegrated,
};

std::string_view integratorName(Integrator i);  // "riemann", "composite", "simpson", "coupled", "decoupled", "preintegrated"
// True for the methods integrated by adaptive_simpson.h rather than by point samples.
inline bool isSimpson(Integrator i) { return i == Integrator::Simpson || i == Integrator::Coupled || i == Integrator::Decoupled; }
Integrator parseIntegrator(std::string_view name, const std::string& what);

template <class Real>
struct RayAccumulator {
    Real r = 0, g = 0, b = 0;
    Real transparency = 1;  // exp(-optical depth so far)

    void add(Integrator integrator, EmissionModel emission, const TransferFunctionSample<Real>& v, Real dx) {
        // A sample without extinction or emission would add exactly 0 and multiply by exactly 1:
        // leaving it out saves the exponential and changes no bit.
        if (v.tau == Real(0) && emission == EmissionModel::ColourTimesExtinction) return;
        const Real attenuation = exponential(-v.tau * dx);
        Real weight;  // multiplies the colour
        if (integrator == Integrator::Riemann) {
            weight = emission == EmissionModel::ColourTimesExtinction ? v.tau * dx : dx;
        } else {
            const Real alpha = -exponentialMinusOne(-v.tau * dx);
            weight = emission == EmissionModel::ColourTimesExtinction ? alpha
                     : v.tau > Real(0)                                 ? alpha / v.tau
                                                                       : dx;
        }
        const Real w = transparency * weight;
        r += w * v.r;
        g += w * v.g;
        b += w * v.b;
        transparency *= attenuation;
    }
    // A pre-integrated segment looked up for the table's length L (preintegration_table.h), standing for
    // lengthRatio times L. The depth scales exactly (the scalar is linear in the segment's fraction, so
    // the depth is the length times the mean extinction over [front, back]); the colour is scaled by the
    // ratio of the alphas, as opacity correction does, which is exact for a ratio of 1 (every segment of
    // Entry and Eye Align on a volume of equal spacings, up to rounding) and for a constant transfer
    // function, and otherwise off by O((ratio - 1) L^2) of the segment's colour.
    // False for a segment exactly 0 in all four, which adds nothing.
    bool addSegment(const SegmentIntegral<Real>& v, Real lengthRatio) {
        if (v.depth == Real(0) && v.r == Real(0) && v.g == Real(0) && v.b == Real(0)) return false;
        const Real depth = v.depth * lengthRatio;
        Real scale = lengthRatio;  // no extinction: the colour grows with the length
        if (lengthRatio == Real(1)) scale = Real(1);
        else if (v.depth > Real(0)) scale = exponentialMinusOne(-depth) / exponentialMinusOne(-v.depth);
        const Real w = transparency * scale;
        r += w * v.r;
        g += w * v.g;
        b += w * v.b;
        transparency *= exponential(-depth);
        return true;
    }
    Real alpha() const { return Real(1) - transparency; }
};

}  // namespace vri
