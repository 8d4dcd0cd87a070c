#pragma once
// One pixel's ray as the fixed-step methods march it, shared by the scalar loop (cpu_renderer.cpp) and
// the packet engine (simd_march.cpp), so that both place every sample alike.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/vec3.hpp>

#include "libvri/core/box.h"
#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/jitter.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/placement.h"

namespace vri {

// One pixel's ray inside the box, in texture coordinates.
template <class Real>
struct TextureRay {
    glm::vec<3, Real> entry, exit;
    double worldLength;
};

// The ray through pixel (px, py) clipped to the box; nullopt when it misses.
template <class Real>
std::optional<TextureRay<Real>> pixelRay(const Camera& camera, const Box& box, int px, int py) {
    using Vec = glm::vec<3, Real>;
    const glm::dvec3 dir = camera.direction(px, py);
    const auto segment = clipRay(camera.eye(), dir, box);
    if (!segment) return std::nullopt;
    return TextureRay<Real>{Vec(box.toTexture(camera.eye() + segment->tNear * dir)),
                            Vec(box.toTexture(camera.eye() + segment->tFar * dir)), segment->tFar - segment->tNear};
}

// Paper A's fixed-step samples along a ray (placement.h), each standing for dx world units of it.
template <class Real>
struct FixedStepSamples {
    using Vec = glm::vec<3, Real>;

    // `jitter`: the fraction of a step past the entry where the first sample goes (jitter.h), or none.
    FixedStepSamples(const TextureRay<Real>& ray, const RenderOptions& opt, const Vec& eyeU, const Vec& dims,
                     std::optional<Real> jitter = std::nullopt)
        : schedule(placed(ray, opt, eyeU, dims, jitter)),
          entry(ray.entry),
          du(schedule.count > 0 ? (ray.exit - ray.entry) / schedule.tEnd : Vec(0)),
          dx(schedule.count > 0
                 ? schedule.tIncr * static_cast<Real>(ray.worldLength / static_cast<double>(schedule.tEnd))
                 : Real(0)) {}

    Vec position(std::int64_t k) const { return entry + schedule.t(k) * du; }
    // Where sample k's segment begins (k = 0 .. count, the last the end of the last segment): half a step
    // before it, so that the segments tile the part of the ray the samples stand for.
    Vec segmentStart(std::int64_t k) const { return entry + (schedule.tStart - halfStep() + static_cast<Real>(k) * schedule.tIncr) * du; }
    Real halfStep() const { return Real(0.5) * schedule.tIncr; }

    SampleSchedule<Real> schedule;
    Vec entry, du;  // sample k at entry + t(k) du
    Real dx;        // world length per sample

private:
    static SampleSchedule<Real> placed(const TextureRay<Real>& ray, const RenderOptions& opt, const Vec& eyeU,
                                       const Vec& dims, std::optional<Real> jitter) {
        SampleSchedule<Real> s =
            placeSamples<Real>(opt.placement, ray.entry, ray.exit, eyeU, dims, static_cast<Real>(opt.samplingRate));
        if (jitter) jitterSchedule(s, *jitter);
        return s;
    }
};

// The samples of FixedStepSamples and the empty-space bricks the ray crosses (occupancy_grid.h), as
// the scalar loop walks them (the packet engine skips by its own test, simd_march.h).
template <class Real>
struct FixedStepRay : FixedStepSamples<Real> {
    using Vec = glm::vec<3, Real>;

    FixedStepRay(const TextureRay<Real>& ray, const RenderOptions& opt, const Vec& eyeU, const Vec& dims,
                 const GridIndexing& indexMap, std::optional<Real> jitter = std::nullopt)
        : FixedStepSamples<Real>(ray, opt, eyeU, dims, jitter),
          indexRay(glm::dvec3(ray.entry) * indexMap.scale - indexMap.offset, glm::dvec3(this->du) * indexMap.scale) {}

    // True when sample k lies past the part of the ray known to be occupied: skipEmpty() must look
    // at the bricks before it is evaluated.
    bool mayBeEmpty(std::int64_t k) const { return static_cast<double>(this->schedule.t(k)) >= knownOccupiedUntil; }

    // The first sample at or after k that is not in an empty brick (schedule.count when none is);
    // every sample skipped contributes exactly nothing. Jumps go to the first sample at or past a
    // brick's exit, counted on the positions evaluated.
    std::int64_t skipEmpty(const OccupancyGrid& occupancy, std::int64_t k) {
        const SampleSchedule<Real>& s = this->schedule;
        while (k < s.count && mayBeEmpty(k)) {
            const auto brick = occupancy.visit(indexRay, static_cast<double>(s.t(k)));
            if (!brick.empty) {
                knownOccupiedUntil = brick.tExit;
                break;
            }
            if (!(brick.tExit < static_cast<double>(s.tEnd))) return s.count;  // the rest of the ray is empty
            auto next = static_cast<std::int64_t>(std::ceil((brick.tExit - s.tStart) / s.tIncr));
            next = std::clamp<std::int64_t>(next, k + 1, s.count);
            while (next > k + 1 && static_cast<double>(s.t(next - 1)) >= brick.tExit)
                --next;
            k = next;
        }
        return k;
    }

    OccupancyGrid::Ray indexRay;
    double knownOccupiedUntil = -std::numeric_limits<double>::infinity();
};

}  // namespace vri
