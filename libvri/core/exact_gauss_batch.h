#pragma once
// The exact method's Gauss rules (exact_ray.cpp) applied to many sub-pieces at once: one ray's
// sub-pieces wait here, structure of arrays, until the batch is full or the ray ends, and are then
// integrated by Highway vectors of doubles, one sub-piece per lane. Each lane performs exact_ray.cpp's
// scalar formulas in the same order, unfused, with exp_kernel.h's exp, so the result is the same
// on every Highway target. Only the choice and application of the rule is batched: the walk, the splits
// and the optical depth in front of each sub-piece stay with the ray, in order.
#include <cstdint>

namespace vri {

struct GaussBatch {
    static constexpr int kCapacity = 64;  // a multiple of the widest target's lanes (8 doubles)

    // Filled by the ray, per sub-piece: s(lambda) = c[0] + c[1] lambda + c[2] lambda^2 + c[3] lambda^3 on
    // lambda in [0, 1]; its length ell; sScale (exact_ray.h); the transfer-function segment it lies in,
    // starting at segmentS, with value[k] + slope[k] (s - segmentS) for k = tau, R, G, B; and the optical
    // depth in front of it.
    alignas(64) double c[4][kCapacity];
    alignas(64) double ell[kCapacity];
    alignas(64) double sScale[kCapacity];
    alignas(64) double segmentS[kCapacity];
    alignas(64) double value[4][kCapacity];
    alignas(64) double slope[4][kCapacity];
    alignas(64) double depthInFront[kCapacity];

    // Results: the transparency in front, exp(-depthInFront); per channel the rule's sum, its error
    // bound and its rounding bound (in units of that transparency, as ExactRay accumulates them) and the
    // bound on the emission g; the panels and nodes of the rule, 0 panels where no Gauss rule reaches the
    // tolerance (that sub-piece needs the adaptive quadrature).
    alignas(64) double front[kCapacity];
    alignas(64) double sum[3][kCapacity];
    alignas(64) double error[3][kCapacity];
    alignas(64) double rounding[3][kCapacity];
    alignas(64) double gMax[3][kCapacity];
    alignas(64) std::int32_t panels[kCapacity];
    alignas(64) std::int32_t nodes[kCapacity];
};

// The cheapest n-point Gauss rule (n <= 3) on k equal panels (k <= 64) whose rigorous error bound
// (gauss_error_bound.h) is at most tolerance / front in every channel, for sub-pieces [0, count).
// Entries from count up to the next whole vector are overwritten with a harmless sub-piece first.
void integrateGaussBatch(GaussBatch& batch, int count, double tolerance, bool colourTimesExtinction);

// The Highway target integrateGaussBatch runs on this CPU (for tests and stats).
const char* gaussBatchTarget();

}  // namespace vri
