#pragma once
// GridSampler for a SparseVolume: the same cell, weights and interpolation (GridSamplerLayout), read from
// the stored block of the brick that holds the cell's lower corner (sparse_volume.h), so that every sample
// is bitwise the dense sampler's.
#include <cstdint>

#include "libvri/core/grid_sampler.h"
#include "libvri/core/sparse_volume.h"

namespace vri {

template <class T, class Real>
class SparseGridSampler {
public:
    using Vec = glm::vec<3, Real>;
    static constexpr int kShift = SparseVolume::kBrickShift, kMask = SparseVolume::kBrick - 1,
                         kBlock = SparseVolume::kBlock;

    SparseGridSampler(const SparseVolume& volume, GridConvention convention)
        : table_(volume.table()),
          blocks_(volume.blocks<T>()),
          bricksX_(volume.bricks().x),
          bricksY_(volume.bricks().y),
          g_(volume.dims, volume.normalisationRange(), convention) {
        // Within a block; 0 along an axis of a single layer, as GridIndexing's strides.
        const std::int64_t strides[3] = {1, kBlock, kBlock * kBlock};
        for (int a = 0; a < 3; ++a) stride_[a] = g_.stride[a] == 0 ? 0 : strides[a];
    }

    Real operator()(const Vec& u) const {
        const auto c = g_.cell(u);
        const std::size_t brick =
            (static_cast<std::size_t>(c.i[2] >> kShift) * bricksY_ + (c.i[1] >> kShift)) * bricksX_ + (c.i[0] >> kShift);
        const std::int64_t local = ((c.i[2] & kMask) * kBlock + (c.i[1] & kMask)) * kBlock + (c.i[0] & kMask);
        const T* p = blocks_ + std::int64_t(table_[brick]) * SparseVolume::kBlockVoxels + local;
        return g_.interpolate(p, stride_, c.w);
    }

private:
    const std::uint32_t* table_;
    const T* blocks_;
    std::size_t bricksX_, bricksY_;
    GridSamplerLayout<Real> g_;
    std::int64_t stride_[3];
};

}  // namespace vri
