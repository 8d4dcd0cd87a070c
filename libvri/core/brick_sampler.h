#pragma once
// The samples of one ray that a brick owns, and GridSampler for a BrickVolume: the cell and weights of the
// whole volume (GridSamplerLayout of its dims), read from the brick's stored box, so that every sample the
// brick owns is bitwise the whole volume's.
#include <cstdint>

#include "libvri/core/brick_volume.h"
#include "libvri/core/grid_sampler.h"

namespace vri {

// The samples k in [begin, end) of one ray that a brick owns, and where its sum goes among the ray's
// bricks: `order` increases along the ray (brick_layers.h composites by it).
struct BrickSamples {
    std::int64_t begin = 0, end = 0;
    int order = 0;
};

// Sample k lies at position(k) (texture coordinates) and the ray moves by `du` per unit of its parameter.
// Along each axis a sample's continuous voxel index x_a(k) is monotone in k: t(k) = tStart + k tIncr, then
// entry + t du, then x scale - offset, each step a correctly rounded monotone function of the one before (no
// contraction: -ffp-contract=off), so the brick index along the axis is monotone too. The samples a brick
// owns along one axis are therefore one run of k, found by bisection, and its run is where the three axes'
// runs meet: the brick index triple never returns to a value it left, and the runs follow the order
// sum over a of sign(du_a) b_a, which grows by at least one from brick to brick. A ray costs a brick
// O(log count) positions, not a walk.
template <class Real, class Position>
BrickSamples brickSamples(const BrickGrid& grid, glm::ivec3 brick, const GridSamplerLayout<Real>& layout,
                          const glm::vec<3, Real>& du, std::int64_t count, const Position& position) {
    BrickSamples run{0, count, 0};
    for (int a = 0; a < 3; ++a) {
        const int sign = du[a] < Real(0) ? -1 : 1;
        run.order += sign * brick[a];
        // The brick along axis a of sample k, counted in the direction the ray goes: monotone non-decreasing.
        const auto along = [&](std::int64_t k) {
            const Real x = position(k)[a] * layout.scale[a] - layout.offset[a];  // as GridSamplerLayout::cell
            return sign * grid.brickAlong(a, static_cast<double>(x));
        };
        const auto firstAbove = [&](int level) {  // the first k whose brick is past `level`, count if none
            std::int64_t lo = 0, hi = count;
            while (lo < hi) {
                const std::int64_t mid = lo + (hi - lo) / 2;
                if (along(mid) > level)
                    hi = mid;
                else
                    lo = mid + 1;
            }
            return lo;
        };
        run.begin = std::max(run.begin, firstAbove(sign * brick[a] - 1));
        run.end = std::min(run.end, firstAbove(sign * brick[a]));
    }
    if (run.begin >= run.end) run.begin = run.end = 0;
    return run;
}

template <class T, class Real>
class BrickGridSampler {
public:
    using Vec = glm::vec<3, Real>;

    // Reads only the cells of the samples the brick owns (ownedSamples), which lie in its stored box
    // (brick_grid.h): sampling elsewhere reads outside its voxels.
    BrickGridSampler(const BrickVolume& brick, GridConvention convention)
        : brick_(brick), data_(brick.voxels.data<T>()), g_(brick.dims(), *brick.voxels.range, convention) {
        const glm::ivec3 s = brick.voxels.dims;
        const std::int64_t strides[3] = {1, s.x, std::int64_t(s.x) * s.y};
        for (int a = 0; a < 3; ++a) stride_[a] = g_.stride[a] == 0 ? 0 : strides[a];
        const glm::ivec3 lo = brick.stored().lo;
        origin_ = lo.x * stride_[0] + lo.y * stride_[1] + lo.z * stride_[2];
    }

    const GridSamplerLayout<Real>& layout() const { return g_; }

    Real operator()(const Vec& u) const {
        const auto c = g_.cell(u);
        const std::int64_t local = c.i[0] * stride_[0] + c.i[1] * stride_[1] + c.i[2] * stride_[2] - origin_;
        return g_.interpolate(data_ + local, stride_, c.w);
    }

    // The samples of a ray the brick owns (brickSamples, below).
    template <class Position>
    BrickSamples ownedSamples(const Vec& du, std::int64_t count, const Position& position) const {
        return brickSamples(brick_.grid, brick_.brick, g_, du, count, position);
    }

private:
    const BrickVolume& brick_;
    const T* data_;
    GridSamplerLayout<Real> g_;
    std::int64_t stride_[3];
    std::int64_t origin_;  // the stored box's first voxel, at the brick's strides
};

template <class Sampler>
inline constexpr bool kIsBrickSampler = false;
template <class T, class Real>
inline constexpr bool kIsBrickSampler<BrickGridSampler<T, Real>> = true;

}  // namespace vri
