#pragma once
// The raw min and max over blocks of a volume's voxels, for the empty-space tests of the occupancy grid
// (occupancy_grid.h) and of the exact method's walk (exact_reference.cpp). Block b of an axis of n voxels
// holds the voxels [b B - before, (b + 1) B + after], clipped to [0, n - 1]. The reduction runs one axis
// at a time, each pass turning the runs along one axis into one value per block, so a voxel is read
// about (B + before + after + 1) / B times instead of the cube of that; every pass is parallel.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

namespace vri {

template <class T>
struct BlockRanges {
    std::vector<T> lo, hi;  // per block, x fastest
};

template <class T>
BlockRanges<T> blockRanges(const T* data, glm::ivec3 dims, glm::ivec3 blocks, int size, int before, int after) {
    BlockRanges<T> r;
    glm::ivec3 n = dims;
    for (int a = 0; a < 3; ++a) {
        const T* srcLo = a == 0 ? data : r.lo.data();  // the volume itself before the first pass
        const T* srcHi = a == 0 ? data : r.hi.data();
        glm::ivec3 m = n;
        m[a] = blocks[a];
        const std::int64_t inner = a == 0 ? 1 : a == 1 ? n[0] : std::int64_t(n[0]) * n[1];
        const std::int64_t outer = a == 0 ? std::int64_t(n[1]) * n[2] : a == 1 ? n[2] : 1;
        std::vector<T> lo(static_cast<std::size_t>(m[0]) * m[1] * m[2]), hi(lo.size());
        using Range = tbb::blocked_range2d<std::int64_t>;
        tbb::parallel_for(Range(0, outer, 0, inner), [&, inner, na = n[a], nb = blocks[a]](const Range& range) {
            for (std::int64_t o = range.rows().begin(); o < range.rows().end(); ++o)
                for (int b = 0; b < nb; ++b) {
                    const int first = std::max(b * size - before, 0), last = std::min((b + 1) * size + after, na - 1);
                    const std::int64_t from = (o * na + first) * inner, to = (o * nb + b) * inner;
                    for (std::int64_t i = range.cols().begin(); i < range.cols().end(); ++i) {
                        T mn = srcLo[from + i], mx = srcHi[from + i];
                        for (int k = 1; k <= last - first; ++k) {
                            mn = std::min(mn, srcLo[from + k * inner + i]);
                            mx = std::max(mx, srcHi[from + k * inner + i]);
                        }
                        lo[to + i] = mn;
                        hi[to + i] = mx;
                    }
                }
        });
        r.lo.swap(lo);
        r.hi.swap(hi);
        n = m;
    }
    return r;
}

}  // namespace vri
