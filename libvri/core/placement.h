#pragma once
// The four fixed-step sample placements of paper A (Steneteg et al., "Volume Raycasting Sampling
// Revisited"), Listings 1-4, computed as written there: in texture coordinates, from the ray's
// entry and exit points, the eye, the volume dimensions and the sampling rate (samples per voxel).
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace vri {

enum class Placement {
    EyeAlign,              // Listing 1: samples on spheres around the eye (Kruger and Westermann)
    EntryAlign,            // Listing 2: first sample half a step after the entry point
    EntryExitAlign,        // Listing 3: step shortened per ray so that floor(samples) fit exactly
    EntryExitAlignCorner,  // Listing 4: ceil() with `dim - 1`, so every ray of positive length gets a sample
                           // (except, as written, one exactly along an axis of a single voxel)
};

std::string_view placementName(Placement p);  // "eye", "entry", "entry-exit", "entry-exit-corner"
Placement parsePlacement(std::string_view name, const std::string& what);

// Sample k (0 <= k < count) lies at t = tStart + k * tIncr along the texture-space ray from the
// entry point, t in [0, tEnd) with tEnd = |exit - entry| in texture units. The shaders of the paper
// advance with `t += tIncr`; we evaluate tStart + k * tIncr directly so that no rounding drifts along
// the ray, and count exactly the samples whose t is below tEnd.
template <class Real>
struct SampleSchedule {
    Real tStart = 0;
    Real tIncr = 0;
    Real tEnd = 0;
    std::int64_t count = 0;
    Real t(std::int64_t k) const { return tStart + static_cast<Real>(k) * tIncr; }
};

// A fixed step's count: as many samples as have t < tEnd, counted on the positions we actually evaluate.
template <class Real>
std::int64_t countBelowEnd(const SampleSchedule<Real>& s) {
    using std::ceil;
    std::int64_t n = s.tStart < s.tEnd ? static_cast<std::int64_t>(ceil((s.tEnd - s.tStart) / s.tIncr)) : 0;
    while (n > 0 && !(s.t(n - 1) < s.tEnd)) --n;
    while (s.t(n) < s.tEnd) ++n;
    return n;
}

template <class Real>
SampleSchedule<Real> placeSamples(Placement placement, const glm::vec<3, Real>& entry,
                                  const glm::vec<3, Real>& exit, const glm::vec<3, Real>& eye,
                                  const glm::vec<3, Real>& dim, Real samplingRate) {
    using std::ceil, std::floor;
    SampleSchedule<Real> s;
    const glm::vec<3, Real> ray = exit - entry;
    s.tEnd = glm::length(ray);
    if (!(s.tEnd > Real(0))) return s;  // a ray that only touches the box: nothing to integrate

    Real samples = 0;
    switch (placement) {
    case Placement::EyeAlign:
    case Placement::EntryAlign:
        samples = glm::length(ray * dim) * samplingRate;
        break;
    case Placement::EntryExitAlign:
        samples = floor(glm::length(ray * dim) * samplingRate);
        break;
    case Placement::EntryExitAlignCorner:
        samples = ceil(samplingRate * glm::length(ray * (dim - glm::vec<3, Real>(1))));
        break;
    }
    // Listing 3 on a ray shorter than one step: no sample at all. (render() bounds the rate, so
    // `samples` is finite and fits an int64.)
    if (!(samples > Real(0)) || !std::isfinite(samples)) return s;
    s.tIncr = s.tEnd / samples;

    if (placement == Placement::EyeAlign) {
        const Real numSteps = glm::length(entry - eye) / s.tIncr;
        s.tStart = (Real(1) - (numSteps - floor(numSteps))) * s.tIncr;  // GLSL fract
    } else {
        s.tStart = Real(0.5) * s.tIncr;
    }

    if (placement == Placement::EntryExitAlign || placement == Placement::EntryExitAlignCorner) {
        s.count = static_cast<std::int64_t>(samples);  // the last sample sits half a step before the exit
    } else {
        s.count = countBelowEnd(s);
    }
    return s;
}

}  // namespace vri
