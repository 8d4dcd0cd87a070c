#pragma once
// Axis-aligned boxes and the clipping of rays against them.
#include <optional>

#include <glm/vec3.hpp>

namespace vri {

struct Box {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{1.0};
    glm::dvec3 size() const { return hi - lo; }
    glm::dvec3 centre() const { return 0.5 * (lo + hi); }
    // Maps a world point to the box's texture coordinates, [0,1]^3 inside the box.
    glm::dvec3 toTexture(const glm::dvec3& p) const { return (p - lo) / (hi - lo); }
};

// Parameter interval [tNear, tFar] of origin + t * dir inside the closed box, with tNear >= 0
// (a ray that starts inside enters at its origin). Rays that only touch a face, an edge or a
// corner hit with tNear == tFar. Axis-parallel rays (dir component exactly 0) are decided by
// whether the origin lies within that slab, never by 0 * inf arithmetic.
struct RayInterval {
    double tNear;
    double tFar;
};
std::optional<RayInterval> clipRay(const glm::dvec3& origin, const glm::dvec3& dir, const Box& box);

}  // namespace vri
