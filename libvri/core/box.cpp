#include "libvri/core/box.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vri {

std::optional<RayInterval> clipRay(const glm::dvec3& origin, const glm::dvec3& dir, const Box& box) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(origin[a]) || !std::isfinite(dir[a])) return std::nullopt;
    double tNear = 0.0;
    double tFar = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return std::nullopt;
            continue;
        }
        double t0 = (box.lo[a] - origin[a]) / dir[a];
        double t1 = (box.hi[a] - origin[a]) / dir[a];
        if (t0 > t1) std::swap(t0, t1);
        tNear = std::max(tNear, t0);
        tFar = std::min(tFar, t1);
        if (tNear > tFar) return std::nullopt;
    }
    return RayInterval{tNear, tFar};
}

}  // namespace vri
