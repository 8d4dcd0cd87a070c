#include "vri/core/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/parallel_for.h>

#include "vri/core/block_ranges.h"

namespace vri {

namespace {

// OccupancyGrid::emptyDistances() of the flags `empty` of a grid of `bricks`. The distance
// max(|dx|, |dy|, |dz|) to the nearest non-empty brick is separable: the distance along x within
// each row, then the nearest of those along y measured as max(|dy|, that), then the same along z.
std::vector<std::int32_t> chebyshevDistances(const std::vector<std::uint8_t>& empty, glm::ivec3 bricks,
                                             std::int32_t cap) {
    std::vector<std::int32_t> d(empty.size());
    for (std::size_t i = 0; i < d.size(); ++i)
        d[i] = empty[i] ? cap : 0;
    const std::size_t stride[3] = {1, static_cast<std::size_t>(bricks.x),
                                   static_cast<std::size_t>(bricks.x) * static_cast<std::size_t>(bricks.y)};
    std::vector<std::int32_t> line;
    for (int a = 0; a < 3; ++a) {
        const int n = bricks[a];
        line.resize(static_cast<std::size_t>(n));
        for (std::size_t start = 0; start < d.size(); ++start) {
            if ((start / stride[a]) % static_cast<std::size_t>(n) != 0) continue;  // not the first of a line
            for (int i = 0; i < n; ++i)
                line[static_cast<std::size_t>(i)] = d[start + static_cast<std::size_t>(i) * stride[a]];
            for (int i = 0; i < n; ++i) {
                std::int32_t best = line[static_cast<std::size_t>(i)];
                for (int j = std::max(0, i - best + 1); j < std::min(n, i + best); ++j)
                    best = std::min(best, std::max(std::abs(i - j), line[static_cast<std::size_t>(j)]));
                d[start + static_cast<std::size_t>(i) * stride[a]] = best;
            }
        }
    }
    return d;
}

}  // namespace

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
    distance_ = chebyshevDistances(empty_, bricks_, kMaxDistance);
}

double OccupancyGrid::emptyFraction() const {
    return empty_.empty() ? 0.0
                          : static_cast<double>(std::count(empty_.begin(), empty_.end(), 1)) / empty_.size();
}

}  // namespace vri
