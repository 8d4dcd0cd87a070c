#pragma once
// Front-to-back accumulation of the emission-absorption integral from point samples.
#include <cmath>
#include <string>
#include <string_view>

#include "libvri/core/float_exp.h"
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
};

std::string_view integratorName(Integrator i);  // "riemann", "composite", "simpson", "coupled", "decoupled"
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
    Real alpha() const { return Real(1) - transparency; }
};

}  // namespace vri
