#include "libvri/core/volume_stats.h"

#include <algorithm>
#include <string>

#include <glm/common.hpp>

#include "libvri/util/error.h"

namespace vri {

namespace {

// The sums and counts of VolumeStats, one value (or n equal ones) at a time.
class StatsAccumulator {
public:
    StatsAccumulator(VolumeStats& stats, int bins, ValueRange data, ValueRange normalisation) : stats_(stats) {
        if (bins < 1) throw Error("histogram needs at least one bin, got " + std::to_string(bins));
        stats.data = data;
        stats.normalisation = normalisation;
        stats.histogram.assign(static_cast<std::size_t>(bins), 0);
        lo_ = normalisation.lo;
        hi_ = normalisation.hi;
        binsPerValue_ = hi_ > lo_ ? bins / (hi_ - lo_) : 0.0;
    }

    void add(double v, std::uint64_t n = 1) {
        sum_ += n == 1 ? v : v * static_cast<double>(n);
        zeros_ += v == 0.0 ? n : 0;
        if (!(v >= lo_)) {
            stats_.below += n;
        } else if (v > hi_) {
            stats_.above += n;
        } else {
            const auto bin = static_cast<std::size_t>((v - lo_) * binsPerValue_);
            stats_.histogram[std::min(bin, stats_.histogram.size() - 1)] += n;
        }
    }

    // The mean, zero fraction and active voxels of `count` voxels added.
    void finish(std::uint64_t count) {
        if (count == 0) return;
        stats_.mean = sum_ / static_cast<double>(count);
        stats_.zeroFraction = static_cast<double>(zeros_) / static_cast<double>(count);
        stats_.activeVoxels = count - zeros_;
    }

private:
    VolumeStats& stats_;
    double lo_, hi_, binsPerValue_;
    double sum_ = 0.0;
    std::uint64_t zeros_ = 0;
};

}  // namespace

VolumeStats computeVolumeStats(const Volume& volume, int bins) {
    VolumeStats stats;
    StatsAccumulator acc(stats, bins, volume.dataRange(), volume.normalisationRange());
    const std::size_t count = volume.voxelCount();
    if (count == 0) return stats;

    const auto bricksAlong = [](int n) { return static_cast<std::size_t>((n + kStatsBrickSize - 1) / kStatsBrickSize); };
    const std::size_t bx = bricksAlong(volume.dims.x), by = bricksAlong(volume.dims.y);
    // One flag per brick: at most a 512th of the voxel count.
    std::vector<bool> brickActive(bx * by * bricksAlong(volume.dims.z), false);
    dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        const T* values = volume.data<T>();
        for (std::size_t i = 0; i < count; ++i) {
            const double v = static_cast<double>(values[i]);
            acc.add(v);
            if (v != 0.0) {
                const std::size_t x = i % volume.dims.x, y = i / volume.dims.x % volume.dims.y,
                                  z = i / volume.dims.x / volume.dims.y;
                brickActive[(z / kStatsBrickSize * by + y / kStatsBrickSize) * bx + x / kStatsBrickSize] = true;
            }
        }
    });
    acc.finish(count);
    stats.bricks = brickActive.size();
    stats.activeBricks = static_cast<std::uint64_t>(std::count(brickActive.begin(), brickActive.end(), true));
    return stats;
}

VolumeStats computeVolumeStats(const SparseVolume& volume, int bins) {
    static_assert(kStatsBrickSize == SparseVolume::kBrick, "the stats' bricks are the sparse volume's");
    VolumeStats stats;
    StatsAccumulator acc(stats, bins, volume.dataRange(), volume.normalisationRange());
    std::uint64_t inStored = 0;  // voxels of the stored bricks; all others are the background
    dispatchVoxelType(volume.type, [&](auto t) {
        using T = decltype(t);
        constexpr int B = SparseVolume::kBlock;
        // In brick order, one brick at a time: the same sums whatever the threads.
        for (std::size_t b = 0; b < volume.brickCount(); ++b) {
            if (volume.table()[b] == 0) continue;
            const glm::ivec3 n = volume.bricks();
            const glm::ivec3 first(static_cast<int>(b % n.x), static_cast<int>(b / n.x % n.y),
                                   static_cast<int>(b / n.x / n.y));
            const glm::ivec3 size = glm::min(glm::ivec3(SparseVolume::kBrick), volume.dims - first * SparseVolume::kBrick);
            const T* p = volume.block<T>(b);
            bool active = false;
            for (int k = 0; k < size.z; ++k)
                for (int j = 0; j < size.y; ++j)
                    for (int i = 0; i < size.x; ++i) {
                        const double v = static_cast<double>(p[(k * B + j) * B + i]);
                        acc.add(v);
                        active = active || v != 0.0;
                    }
            inStored += static_cast<std::uint64_t>(size.x) * size.y * size.z;
            stats.activeBricks += active;
        }
    });
    const std::uint64_t count = volume.voxelCount();
    acc.add(volume.background(), count - inStored);
    acc.finish(count);
    stats.bricks = volume.brickCount();
    if (volume.background() != 0.0) stats.activeBricks += volume.brickCount() - volume.storedBricks();
    return stats;
}

}  // namespace vri
