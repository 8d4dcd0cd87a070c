#pragma once
// The range of tau h where the Simpson methods' outputs mean what they say, and what a render counted
// beyond it.
//
// Within a step of h voxels (adaptive_simpson.h) the transparency at the five points t + k h / 4 comes
// from quadratures of the extinction kappa: at the quarter points, the integral of the quadratic through
// a half's three points, h / 48 (5 k_0 + 8 k_1 - k_2), which is negative where kappa rises steeply, so
// that T there exceeds the step's entry transparency by up to exp(kappa_max h / 48). Alpha and colour then
// take Boole's weights (or paper B's D + |D - S| / 15) of kappa T. With x = kappa_max h (tau per world
// unit times the step in world units: the optical depth of one step at its largest extinction):
//  - constant kappa: a step's alpha is (x / 180)(14 + 64 e^-x/4 + 24 e^-x/2 + 64 e^-3x/4 + 14 e^-x), 1 at
//    x = 5.25 and 0.078 x beyond, where the integral is 1 - e^-x < 1;
//  - any kappa in [0, kappa_max] at the five points: one step from full transparency gives an alpha above
//    1 from x = 3.94 (Richardson, at kappa = (0, 0.98, 1, 1, 1) kappa_max) and 3.63 (paper B's form, at
//    (1, 0.33, 1, 1, 1)), found by a search over the five values (tests/unit/simpson_range_test.cpp
//    repeats it on the integrator itself);
//  - far beyond, the largest value grows as (64 / 180) 6 e^(x/48 - 1) = 0.785 e^(x/48) (kappa rising
//    at the last quarter point): a float image overflows from x = 48 ln(FLT_MAX / 0.785) = 4.27e3, the
//    quarter points' transparency itself in double from 48 ln(DBL_MAX) = 3.4e4.
// Below the limit a value may still exceed 1 by the quadrature's error (Boole's rule overestimates
// the integral of kappa e^-kappa v a little), which shrinks with h as the method converges; beyond it one
// step alone may leave [0, 1] by an amount that no tolerance controls. A render counts the rays that took
// an accepted step beyond the limit (x the step times the largest of its five extinctions).
#include <algorithm>
#include <cstdint>
#include <string>

#include "libvri/core/adaptive_simpson.h"

namespace vri {

// The largest x = tau h for which no extinction profile makes one step's alpha exceed 1 (above; rounded
// down to three digits).
inline double simpsonStepDepthLimit(AcceptedValue accepted) {
    return accepted == AcceptedValue::Richardson ? 3.93 : 3.62;
}

// What a render's rays did against that limit.
struct SimpsonRange {
    double limit = 0.0;               // simpsonStepDepthLimit of the run
    double largest = 0.0;             // the largest tau h of an accepted step, over every ray
    std::uint64_t pixelsBeyond = 0;   // rays that took an accepted step beyond the limit

    void addRay(double rayLargest) {
        largest = std::max(largest, rayLargest);
        if (rayLargest > limit) ++pixelsBeyond;
    }
    void merge(const SimpsonRange& other) {
        largest = std::max(largest, other.largest);
        pixelsBeyond += other.pixelsBeyond;
    }
    // "N of RAYS pixels took Simpson steps of tau h up to X, beyond LIMIT where ...", for a warning.
    std::string describe(std::uint64_t rays) const;
};

}  // namespace vri
