#include "vri/core/volume_stats.h"

#include <algorithm>
#include <string>

#include "vri/util/error.h"

namespace vri {

VolumeStats computeVolumeStats(const Volume& volume, int bins) {
    if (bins < 1) throw Error("histogram needs at least one bin, got " + std::to_string(bins));
    VolumeStats stats;
    stats.data = volume.dataRange();
    stats.normalisation = volume.normalisationRange();
    stats.histogram.assign(static_cast<std::size_t>(bins), 0);
    const std::size_t count = volume.voxelCount();
    if (count == 0) return stats;

    const double lo = stats.normalisation.lo;
    const double hi = stats.normalisation.hi;
    const double binsPerValue = hi > lo ? bins / (hi - lo) : 0.0;
    double sum = 0.0;
    std::size_t zeros = 0;
    const auto bricksAlong = [](int n) { return static_cast<std::size_t>((n + kStatsBrickSize - 1) / kStatsBrickSize); };
    const std::size_t bx = bricksAlong(volume.dims.x), by = bricksAlong(volume.dims.y);
    // One flag per brick: at most a 512th of the voxel count.
    std::vector<bool> brickActive(bx * by * bricksAlong(volume.dims.z), false);
    dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        const T* values = volume.data<T>();
        for (std::size_t i = 0; i < count; ++i) {
            const double v = static_cast<double>(values[i]);
            sum += v;
            zeros += v == 0.0;
            if (v != 0.0) {
                const std::size_t x = i % volume.dims.x, y = i / volume.dims.x % volume.dims.y,
                                  z = i / volume.dims.x / volume.dims.y;
                brickActive[(z / kStatsBrickSize * by + y / kStatsBrickSize) * bx + x / kStatsBrickSize] = true;
            }
            if (!(v >= lo)) {
                ++stats.below;
            } else if (v > hi) {
                ++stats.above;
            } else {
                const auto bin = static_cast<std::size_t>((v - lo) * binsPerValue);
                ++stats.histogram[std::min(bin, stats.histogram.size() - 1)];
            }
        }
    });
    stats.mean = sum / static_cast<double>(count);
    stats.zeroFraction = static_cast<double>(zeros) / static_cast<double>(count);
    stats.activeVoxels = count - zeros;
    stats.bricks = brickActive.size();
    stats.activeBricks = static_cast<std::uint64_t>(std::count(brickActive.begin(), brickActive.end(), true));
    return stats;
}

}  // namespace vri
