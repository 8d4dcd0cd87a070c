#include "vri/core/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/parallel_for.h>

#include "vri/core/block_ranges.h"

namespace vri {

OccupancyGrid::OccupancyGrid(const Volume& volume, GridConvention, const TransferFunction& tf)
    : dims_(volume.dims), maxIndex_(glm::dvec3(volume.dims) - glm::dvec3(1.0)) {
    // Bricks tile the index range [0, n - 1] of each axis: brick m holds indices [m B, (m + 1) B).
    for (int a = 0; a < 3; ++a) bricks_[a] = (dims_[a] - 1) / kBrick + 1;
    empty_.assign(static_cast<std::size_t>(bricks_.x) * bricks_.y * bricks_.z, 0);
    const ValueRange range = volume.normalisationRange();
    const double invRange = range.hi > range.lo ? 1.0 / (range.hi - range.lo) : 0.0;
    // Each brick's voxels plus a one-voxel margin on every side.
    const auto [lo, hi] = dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        const BlockRanges<T> r = blockRanges(volume.data<T>(), dims_, bricks_, kBrick, 1, 1);
        return std::pair<std::vector<double>, std::vector<double>>{std::vector<double>(r.lo.begin(), r.lo.end()),
                                                                   std::vector<double>(r.hi.begin(), r.hi.end())};
    });
    tbb::parallel_for(std::size_t(0), empty_.size(), [&](std::size_t i) {
        const double mn = lo[i], mx = hi[i];
        const double s0 = (mn - range.lo) * invRange, s1 = (mx - range.lo) * invRange;
        // A float sampler rounds lo, 1 / (hi - lo) and the interpolated value to float:
        // errors of a few float ulps of |lo|, |mn|, |mx|, scaled by 1 / (hi - lo). Pad by far more.
        const double magnitude = 1.0 + (std::abs(range.lo) + std::abs(mn) + std::abs(mx)) * invRange;
        const double pad = 1e-5 * magnitude;
        empty_[i] = tf.isInvisible(s0 - pad, s1 + pad);
    });
}

double OccupancyGrid::emptyFraction() const {
    return empty_.empty() ? 0.0
                          : static_cast<double>(std::count(empty_.begin(), empty_.end(), 1)) / empty_.size();
}

}  // namespace vri
