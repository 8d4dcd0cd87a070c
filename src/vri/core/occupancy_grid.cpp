#include "vri/core/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <tbb/parallel_for.h>

namespace vri {

namespace {

// Raw min..max over the voxels [lo, hi] (inclusive, already clipped to the volume).
template <class T>
std::pair<double, double> rawRange(const Volume& v, glm::ivec3 lo, glm::ivec3 hi) {
    const T* d = v.data<T>();
    T mn = d[v.index(lo.x, lo.y, lo.z)], mx = mn;
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y) {
            const T* row = d + v.index(0, y, z);
            for (int x = lo.x; x <= hi.x; ++x) {
                mn = std::min(mn, row[x]);
                mx = std::max(mx, row[x]);
            }
        }
    return {static_cast<double>(mn), static_cast<double>(mx)};
}

}  // namespace

OccupancyGrid::OccupancyGrid(const Volume& volume, GridConvention, const TransferFunction& tf)
    : dims_(volume.dims), maxIndex_(glm::dvec3(volume.dims) - glm::dvec3(1.0)) {
    // Bricks tile the index range [0, n - 1] of each axis: brick m holds indices [m B, (m + 1) B).
    for (int a = 0; a < 3; ++a) bricks_[a] = (dims_[a] - 1) / kBrick + 1;
    empty_.assign(static_cast<std::size_t>(bricks_.x) * bricks_.y * bricks_.z, 0);
    const ValueRange range = volume.normalisationRange();
    const double invRange = range.hi > range.lo ? 1.0 / (range.hi - range.lo) : 0.0;
    tbb::parallel_for(0, bricks_.z, [&](int bz) {
        for (int by = 0; by < bricks_.y; ++by)
            for (int bx = 0; bx < bricks_.x; ++bx) {
                const glm::ivec3 b(bx, by, bz);
                const glm::ivec3 lo = glm::max(b * kBrick - 1, glm::ivec3(0));
                const glm::ivec3 hi = glm::min((b + 1) * kBrick + 1, dims_ - 1);
                const auto [mn, mx] = dispatchVoxelType(volume.type, [&](auto t) {
                    return rawRange<decltype(t)>(volume, lo, hi);
                });
                const double s0 = (mn - range.lo) * invRange, s1 = (mx - range.lo) * invRange;
                // A float sampler rounds lo, 1 / (hi - lo) and the interpolated value to float:
                // errors of a few float ulps of |lo|, |mn|, |mx|, scaled by 1 / (hi - lo). Pad by far more.
                const double magnitude = 1.0 + (std::abs(range.lo) + std::abs(mn) + std::abs(mx)) * invRange;
                const double pad = 1e-5 * magnitude;
                empty_[(static_cast<std::size_t>(bz) * bricks_.y + by) * bricks_.x + bx] =
                    tf.isInvisible(s0 - pad, s1 + pad);
            }
    });
}

double OccupancyGrid::emptyFraction() const {
    return empty_.empty() ? 0.0
                          : static_cast<double>(std::count(empty_.begin(), empty_.end(), 1)) / empty_.size();
}

}  // namespace vri
