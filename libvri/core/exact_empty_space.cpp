#include "libvri/core/exact_empty_space.h"

#include <algorithm>
#include <type_traits>

#include <tbb/parallel_for.h>

#include "libvri/core/block_ranges.h"

namespace vri {

ExactEmptySpace::ExactEmptySpace(const Volume& volume, const TransferFunction& tf) : tf_(tf) {
    const ValueRange r = volume.normalisationRange();
    lo_ = r.lo;
    invRange_ = r.hi > r.lo ? 1.0 / (r.hi - r.lo) : 0.0;
    for (int a = 0; a < 3; ++a) {
        const int maxBase = std::max(volume.dims[a] - 2, 0);  // the largest base corner of a cell
        blocks_[a] = (maxBase >> kBlockShift) + 1;
        regions_[a] = ((blocks_[a] - 1) >> kRegionShift) + 1;
    }
    dispatchVoxelType(volume.type, [&](auto voxel) {
        using T = decltype(voxel);
        // For 8- and 16-bit voxels, the largest raw value up to which a range whose smallest value is v
        // stays invisible: the TF is zero on [s0, s1] only if it is on every sub-interval, so the
        // bound grows with v and a single pass finds it.
        if constexpr (std::is_same_v<T, std::uint8_t> || std::is_same_v<T, std::uint16_t>) {
            constexpr int count = 1 << (8 * sizeof(T));
            invisibleUpTo_.resize(count);
            auto s = [&](int raw) { return (raw - lo_) * invRange_; };
            int hi = -1;
            for (int v = 0; v < count; ++v) {
                hi = std::max(hi, v - 1);
                while (hi + 1 < count && tf.isInvisible(s(v), s(hi + 1))) ++hi;
                invisibleUpTo_[v] = hi;
            }
        }
        const BlockRanges<T> ranges = blockRanges(volume.data<T>(), volume.dims, blocks_, 1 << kBlockShift, 0, 0);
        emptyBlock_.resize(ranges.lo.size());
        tbb::parallel_for(std::size_t(0), ranges.lo.size(), [&](std::size_t i) {
            emptyBlock_[i] = invisible(static_cast<double>(ranges.lo[i]), static_cast<double>(ranges.hi[i]));
        });
    });
    emptyRegion_.assign(static_cast<std::size_t>(regions_.x) * regions_.y * regions_.z, 1);
    for (int z = 0; z < blocks_.z; ++z)
        for (int y = 0; y < blocks_.y; ++y)
            for (int x = 0; x < blocks_.x; ++x)
                if (!emptyBlock_[index(x, y, z, blocks_)])
                    emptyRegion_[index(x >> kRegionShift, y >> kRegionShift, z >> kRegionShift, regions_)] = 0;
}

}  // namespace vri
