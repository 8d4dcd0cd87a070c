#pragma once
// GridSampler for a BrickVolume: the cell and weights of the whole volume (GridSamplerLayout of its
// dims), read from the brick's stored box, so that every sample the brick owns is bitwise the whole
// volume's; and the samples of one ray that a brick owns.
#include <cstdint>

#include "libvri/core/brick_volume.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/util/error.h"

namespace vri {

template <class T, class Real>
class BrickGridSampler {
public:
    using Vec = glm::vec<3, Real>;

    BrickGridSampler(const BrickVolume& brick, GridConvention convention)
        : data_(brick.voxels.data<T>()), lo_(brick.stored.lo), g_(brick.dims, *brick.voxels.range, convention) {
        const glm::ivec3 s = brick.stored.size();
        const std::int64_t strides[3] = {1, s.x, std::int64_t(s.x) * s.y};
        for (int a = 0; a < 3; ++a) {
            stride_[a] = g_.stride[a] == 0 ? 0 : strides[a];
            // The highest lower corner whose stencil the stored box holds (the corner itself where the
            // whole volume has one layer along the axis, both taps reading it).
            maxLocal_[a] = s[a] - (g_.stride[a] == 0 ? 1 : 2);
        }
    }

    const GridSamplerLayout<Real>& layout() const { return g_; }

    Real operator()(const Vec& u) const {
        const auto c = g_.cell(u);
        std::int64_t local = 0;
        for (int a = 0; a < 3; ++a) {
            const int i = c.i[a] - lo_[a];
            // brickSamples (below) keeps a brick's samples within one voxel of its planes: never reached.
            if (i < 0 || i > maxLocal_[a])
                throw Error("bricks: a sample's cell lies outside its brick's stored voxels");
            local += i * stride_[a];
        }
        return g_.interpolate(data_ + local, stride_, c.w);
    }

private:
    const T* data_;
    glm::ivec3 lo_;
    GridSamplerLayout<Real> g_;
    std::int64_t stride_[3];
    int maxLocal_[3];
};

// The samples k in [begin, end) of one ray that a brick owns, and where its sum goes among the ray's
// bricks: `order` increases along the ray (brick_layers.h composites by it).
struct BrickSamples {
    std::int64_t begin = 0, end = 0;
    int order = 0;
};

// Sample k lies at position(k) (texture coordinates) and the ray moves by `du` per unit of its parameter.
// Along each axis the brick a sample belongs to is made monotone along the ray (the largest so far where
// the ray goes up the axis, the smallest where it goes down): in exact arithmetic it already is, and
// rounding an ulp back across a plane must not split a brick's samples in two. The brick index triple so
// never returns to a value it left, each brick's samples are one run of k, and the runs follow the order
// sum over a of sign(du_a) b_a, which grows by at least one from brick to brick. A ray walks its samples'
// positions from the first up to the end of its run in `brick` (not their scalars).
template <class Real, class Position>
BrickSamples brickSamples(const BrickGrid& grid, glm::ivec3 brick, const GridSamplerLayout<Real>& layout,
                          const glm::vec<3, Real>& du, std::int64_t count, const Position& position) {
    BrickSamples run{count, count, 0};
    int sign[3];
    for (int a = 0; a < 3; ++a) {
        sign[a] = du[a] < Real(0) ? -1 : 1;
        run.order += sign[a] * brick[a];
    }
    glm::ivec3 owner{0};
    for (std::int64_t k = 0; k < count; ++k) {
        const glm::vec<3, Real> x = position(k) * layout.scale - layout.offset;  // as GridSamplerLayout::cell
        bool beyond = false;
        for (int a = 0; a < 3; ++a) {
            const int b = grid.brickAlong(a, static_cast<double>(x[a]));
            owner[a] = k == 0 ? b : sign[a] > 0 ? std::max(owner[a], b) : std::min(owner[a], b);
            beyond = beyond || sign[a] * (owner[a] - brick[a]) > 0;
        }
        if (owner == brick) {
            if (run.begin == count) run.begin = k;
            run.end = k + 1;
        } else if (beyond) {
            break;  // past the brick along some axis: it never returns
        }
    }
    if (run.begin == count) run.begin = run.end = 0;
    return run;
}

}  // namespace vri
