#include "libvri/core/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include <glm/vector_relational.hpp>
#include <tbb/parallel_for.h>

#include "libvri/core/block_ranges.h"

namespace vri {

namespace {

// Whether a brick whose voxels (and margin) span the raw values mn..mx is invisible: to the transfer
// function, or to a pre-integration table (its lookups there are exactly 0).
class EmptinessTest {
public:
    EmptinessTest(const ValueRange& range, std::function<bool(double, double)> invisible)
        : range_(range), invRange_(range.hi > range.lo ? 1.0 / (range.hi - range.lo) : 0.0),
          invisible_(std::move(invisible)) {}

    bool operator()(double mn, double mx) const {
        const double s0 = (mn - range_.lo) * invRange_, s1 = (mx - range_.lo) * invRange_;
        // A float sampler rounds lo, 1 / (hi - lo) and the interpolated value to float:
        // errors of a few float ulps of |lo|, |mn|, |mx|, scaled by 1 / (hi - lo). Pad by far more.
        const double magnitude = 1.0 + (std::abs(range_.lo) + std::abs(mn) + std::abs(mx)) * invRange_;
        const double pad = 1e-5 * magnitude;
        return invisible_(s0 - pad, s1 + pad);
    }

private:
    ValueRange range_;
    double invRange_;
    std::function<bool(double, double)> invisible_;
};

std::function<bool(double, double)> invisibleTo(const TransferFunction& tf) {
    return [&tf](double s0, double s1) { return tf.isInvisible(s0, s1); };
}

// Per block of `size` voxels (x fastest), 1 when isEmpty holds for the range of its voxels, the first of
// the next block and `margin` more on each side: blockRanges()' blocks [b B - margin, (b + 1) B + margin].
std::vector<std::uint8_t> emptyBlocks(const Volume& volume, glm::ivec3 blocks, int size, int margin,
                                      const EmptinessTest& isEmpty) {
    std::vector<std::uint8_t> empty(static_cast<std::size_t>(blocks.x) * blocks.y * blocks.z);
    dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        const BlockRanges<T> r = blockRanges(volume.data<T>(), volume.dims, blocks, size, margin, margin);
        tbb::parallel_for(std::size_t(0), empty.size(), [&](std::size_t i) {
            empty[i] = isEmpty(static_cast<double>(r.lo[i]), static_cast<double>(r.hi[i]));
        });
    });
    return empty;
}

// StencilBricks::distances() of one octant, from the flags `empty` of a grid of `bricks`: along an
// axis with ahead = +1 (-1) only the bricks of equal or higher (lower) index count. The distance
// max(|dx|, |dy|, |dz|) to the nearest non-empty brick is separable: the distance along x within each
// row, then the nearest of those along y measured as max(|dy|, that), then the same along z.
std::vector<std::int32_t> chebyshevDistances(const std::vector<std::uint8_t>& empty, glm::ivec3 bricks,
                                             std::int32_t cap, glm::ivec3 ahead) {
    std::vector<std::int32_t> d(empty.size());
    for (std::size_t i = 0; i < d.size(); ++i)
        d[i] = empty[i] ? cap : 0;
    const std::size_t stride[3] = {1, static_cast<std::size_t>(bricks.x),
                                   static_cast<std::size_t>(bricks.x) * static_cast<std::size_t>(bricks.y)};
    for (int a = 0; a < 3; ++a) {
        const int n = bricks[a];
        // The lines along axis a start at the bricks whose index along a is 0: `lines` of them, line l
        // at (l % stride) + (l / stride) * stride * n.
        const std::size_t lines = d.size() / static_cast<std::size_t>(n);
        tbb::parallel_for(std::size_t(0), lines, [&, n, s = stride[a], look = ahead[a]](std::size_t l) {
            const std::size_t start = l % s + l / s * s * static_cast<std::size_t>(n);
            std::vector<std::int32_t> line(static_cast<std::size_t>(n));
            for (int i = 0; i < n; ++i)
                line[static_cast<std::size_t>(i)] = d[start + static_cast<std::size_t>(i) * s];
            for (int i = 0; i < n; ++i) {
                // Bricks j ahead of i, `steps` away, until none nearer than `best` can be left.
                std::int32_t best = line[static_cast<std::size_t>(i)];
                for (int j = i + look, steps = 1; steps < best && j >= 0 && j < n; j += look, ++steps)
                    best = std::min(best, std::max(steps, line[static_cast<std::size_t>(j)]));
                d[start + static_cast<std::size_t>(i) * s] = best;
            }
        });
    }
    return d;
}

}  // namespace

OccupancyGrid::OccupancyGrid(glm::ivec3 dims) : dims_(dims), maxIndex_(glm::dvec3(dims) - glm::dvec3(1.0)) {
    // Bricks tile the index range [0, n - 1] of each axis: brick m holds indices [m B, (m + 1) B).
    for (int a = 0; a < 3; ++a) bricks_[a] = (dims_[a] - 1) / kBrick + 1;
    empty_.assign(static_cast<std::size_t>(bricks_.x) * bricks_.y * bricks_.z, 0);
}

OccupancyGrid::OccupancyGrid(const Volume& volume, GridConvention, const TransferFunction& tf)
    : OccupancyGrid(volume.dims) {
    const EmptinessTest isEmpty(volume.normalisationRange(), invisibleTo(tf));
    // Each brick's voxels plus a one-voxel margin on every side.
    empty_ = emptyBlocks(volume, bricks_, kBrick, 1, isEmpty);
}

OccupancyGrid::OccupancyGrid(const Volume& volume, GridConvention, const PreintegrationTable& table)
    : OccupancyGrid(volume.dims) {
    const EmptinessTest isEmpty(volume.normalisationRange(),
                                [&table](double s0, double s1) { return table.isInvisible(s0, s1); });
    empty_ = emptyBlocks(volume, bricks_, kBrick, 1, isEmpty);
}

OccupancyGrid::OccupancyGrid(const SparseVolume& volume, GridConvention, const TransferFunction& tf)
    : OccupancyGrid(volume.dims) {
    static_assert(kBrick == SparseVolume::kBrick, "the occupancy grid's bricks are the sparse volume's");
    const EmptinessTest isEmpty(volume.normalisationRange(), invisibleTo(tf));
    const double background = volume.background();
    std::fill(empty_.begin(), empty_.end(), isEmpty(background, background));
    // Brick m's voxels and margin, [8m - 1, 8m + 9] along each axis as blockRanges takes them above, are
    // the last voxel of brick m - 1, the voxels of brick m and the first two of brick m + 1: only bricks
    // next to a stored one can see anything but the background.
    std::vector<std::uint8_t> near(empty_.size(), 0);
    for (int z = 0; z < bricks_.z; ++z)
        for (int y = 0; y < bricks_.y; ++y)
            for (int x = 0; x < bricks_.x; ++x) {
                if (volume.table()[volume.brickIndex(x, y, z)] == 0) continue;
                for (int nz = std::max(z - 1, 0); nz <= std::min(z + 1, bricks_.z - 1); ++nz)
                    for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, bricks_.y - 1); ++ny)
                        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, bricks_.x - 1); ++nx)
                            near[volume.brickIndex(nx, ny, nz)] = 1;
            }
    dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        constexpr int B = SparseVolume::kBlock;
        tbb::parallel_for(std::size_t(0), empty_.size(), [&](std::size_t i) {
            if (!near[i]) return;
            const glm::ivec3 m(static_cast<int>(i % bricks_.x), static_cast<int>(i / bricks_.x % bricks_.y),
                               static_cast<int>(i / bricks_.x / bricks_.y));
            T mn = std::numeric_limits<T>::max(), mx = std::numeric_limits<T>::lowest();
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec3 d(dx, dy, dz), n = m + d;
                        if (glm::any(glm::lessThan(n, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(n, bricks_)))
                            continue;
                        // Brick n's own voxels in the margin (its last one, or its first two) or all of
                        // them, clipped to the volume.
                        glm::ivec3 first, last;
                        for (int a = 0; a < 3; ++a) {
                            first[a] = d[a] < 0 ? kBrick - 1 : 0;
                            last[a] = std::min(d[a] < 0 ? kBrick - 1 : d[a] > 0 ? 1 : kBrick - 1,
                                               dims_[a] - 1 - n[a] * kBrick);
                        }
                        const T* p = volume.block<T>(volume.brickIndex(n.x, n.y, n.z));
                        for (int z = first.z; z <= last.z; ++z)
                            for (int y = first.y; y <= last.y; ++y)
                                for (int x = first.x; x <= last.x; ++x) {
                                    const T v = p[(z * B + y) * B + x];
                                    mn = std::min(mn, v);
                                    mx = std::max(mx, v);
                                }
                    }
            empty_[i] = isEmpty(static_cast<double>(mn), static_cast<double>(mx));
        });
    });
}

double OccupancyGrid::emptyFraction() const {
    return empty_.empty() ? 0.0
                          : static_cast<double>(std::count(empty_.begin(), empty_.end(), 1)) / empty_.size();
}

StencilBricks::StencilBricks(const Volume& volume, GridConvention, const TransferFunction& tf) {
    findEmpty(volume, invisibleTo(tf));
}

StencilBricks::StencilBricks(const Volume& volume, GridConvention, const PreintegrationTable& table) {
    findEmpty(volume, [&table](double s0, double s1) { return table.isInvisible(s0, s1); });
}

void StencilBricks::findEmpty(const Volume& volume, const std::function<bool(double, double)>& invisible) {
    const int size = 1 << kShift;
    for (int a = 0; a < 3; ++a) bricks_[a] = (volume.dims[a] - 1) / size + 1;
    // Each brick's voxels and the next one's first (the stencils' far corners).
    empty_ = emptyBlocks(volume, bricks_, size, 0, EmptinessTest(volume.normalisationRange(), invisible));
    distance_.assign(8 * empty_.size() + 3, 0);
}

void StencilBricks::addOctants(unsigned octants) {
    static_assert(kMaxDistance <= 255);
    const unsigned missing = octants & 0xFFu & ~octants_;
    tbb::parallel_for(0, 8, [&](int octant) {
        if (!(missing >> octant & 1u)) return;
        const glm::ivec3 ahead(octant & 1 ? -1 : 1, octant & 2 ? -1 : 1, octant & 4 ? -1 : 1);
        const std::vector<std::int32_t> d = chebyshevDistances(empty_, bricks_, kMaxDistance, ahead);
        std::copy(d.begin(), d.end(), distance_.begin() + static_cast<std::ptrdiff_t>(octant * empty_.size()));
    });
    octants_ |= missing;
}

unsigned rayOctants(const Camera& camera) {
    unsigned below[3] = {0, 0, 0};  // per axis: bit 0 for a component >= 0, bit 1 for one < 0
    for (const int px : {0, camera.width() - 1})
        for (const int py : {0, camera.height() - 1}) {
            const glm::dvec3 d = camera.direction(px, py);
            for (int a = 0; a < 3; ++a) below[a] |= d[a] < 0.0 ? 2u : 1u;
        }
    unsigned octants = 0;
    for (unsigned o = 0; o < 8; ++o)
        if ((below[0] >> (o & 1) & 1) && (below[1] >> (o >> 1 & 1) & 1) && (below[2] >> (o >> 2 & 1) & 1))
            octants |= 1u << o;
    return octants;
}

}  // namespace vri
