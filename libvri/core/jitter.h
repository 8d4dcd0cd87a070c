#pragma once
// Jittered sampling (VTK's UseJittering, OSPRay, most GPU ray casters): the first sample of a pixel's ray
// is moved to a random fraction of the step past the entry, which trades paper A's wood-grain pattern
// (every ray's samples at the same phase) for noise that averaging frames removes. The fraction comes
// from a hash of the pixel and the seed, not from a random number generator's state, so a pixel's value
// never depends on the order the pixels are computed in, the thread count or the tiling, and the GLSL
// shaders compute the same 32-bit integer arithmetic.
#include <cstdint>

#include "libvri/core/placement.h"

namespace vri {

// Chris Wellons' "lowbias32" integer finaliser (two xor-shift-multiply rounds): every input bit changes
// every output bit with probability close to 1/2.
inline std::uint32_t mixBits(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// The jitter of pixel (px, py) under `seed`: a multiple of 2^-24 in [0, 1), exact in float and double.
inline double jitterFraction(int px, int py, std::uint32_t seed) {
    const std::uint32_t h = mixBits(static_cast<std::uint32_t>(px) ^ mixBits(static_cast<std::uint32_t>(py) ^ mixBits(seed)));
    return static_cast<double>(h >> 8) * 0x1p-24;
}

// Moves a placement's first sample to `fraction` of its step past the entry (0 <= fraction < 1; the mean,
// 1/2, is Entry Align's), the step kept and the count recomputed on the positions evaluated.
template <class Real>
void jitterSchedule(SampleSchedule<Real>& s, Real fraction) {
    if (!(s.tIncr > Real(0))) return;  // no sample at all
    s.tStart = fraction * s.tIncr;
    s.count = countBelowEnd(s);
}

}  // namespace vri
