#include "libvri/core/sparse_volume.h"

#include <limits>
#include <mutex>
#include <string>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri {

namespace {

std::string describe(glm::ivec3 d, VoxelType t) {
    return "a sparse " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z) + " " +
           std::string(voxelTypeName(t)) + " volume";
}

}  // namespace

SparseVolume::SparseVolume(glm::ivec3 d, VoxelType t, double background) : dims(d), type(t), background_(background) {
    if (d.x < 1 || d.y < 1 || d.z < 1)
        throw Error("volume dimensions must be at least 1x1x1, got " + std::to_string(d.x) + "x" +
                    std::to_string(d.y) + "x" + std::to_string(d.z));
    bricks_ = bricksOf(d);
    const std::size_t tableBytes =
        checkedBytes(describe(d, t) + "'s brick table",
                     {std::uint64_t(bricks_.x), std::uint64_t(bricks_.y), std::uint64_t(bricks_.z), sizeof(std::uint32_t)});
    table_.assign(tableBytes / sizeof(std::uint32_t), 0);
}

void SparseVolume::allocateBlocks(std::size_t blocks) {
    if (blocks > std::numeric_limits<std::uint32_t>::max())
        throw Error(describe(dims, type) + ": " + std::to_string(blocks) + " bricks, more than a 32-bit table holds");
    // The blocks and the table together, as the byte count a dense volume is checked by.
    const std::string what = describe(dims, type) + " (" + std::to_string(blocks - 1) + " stored bricks of " +
                             std::to_string(kBlock) + "^3 voxels and the brick table)";
    const std::size_t bytes =
        checkedBytes(what, {std::uint64_t(blocks) * kBlockVoxels * voxelSize(type) + table_.size() * sizeof(std::uint32_t)});
    allocateOrExplain(what, bytes, [&] { voxels_.assign(blocks * kBlockVoxels * voxelSize(type), std::byte{0}); });
    blocks_ = blocks;
}

std::size_t SparseVolume::voxelCount() const {
    return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
}

double SparseVolume::value(int x, int y, int z) const {
    const std::size_t brick = brickIndex(x >> kBrickShift, y >> kBrickShift, z >> kBrickShift);
    const int local = (((z & (kBrick - 1)) * kBlock) + (y & (kBrick - 1))) * kBlock + (x & (kBrick - 1));
    return dispatchVoxelType(type, [&](auto t) { return static_cast<double>(block<decltype(t)>(brick)[local]); });
}

ValueRange SparseVolume::dataRange() const {
    return dispatchVoxelType(type, [&](auto t) {
        using T = decltype(t);
        std::mutex mutex;
        // Every brick not stored holds the background only.
        const bool anyBackgroundBrick = storedBricks() < brickCount();
        T lo = anyBackgroundBrick ? static_cast<T>(background_) : std::numeric_limits<T>::max();
        T hi = anyBackgroundBrick ? static_cast<T>(background_) : std::numeric_limits<T>::lowest();
        forEachStoredBrick([&](std::size_t b, int, int, int, int nx, int ny, int nz) {
            const T* p = block<T>(b);
            T mn = p[0], mx = p[0];
            for (int k = 0; k < nz; ++k)
                for (int j = 0; j < ny; ++j)
                    for (int i = 0; i < nx; ++i) {
                        const T value = p[(k * kBlock + j) * kBlock + i];
                        mn = std::min(mn, value);
                        mx = std::max(mx, value);
                    }
            const std::lock_guard lock(mutex);
            lo = std::min(lo, mn);
            hi = std::max(hi, mx);
        });
        return ValueRange{static_cast<double>(lo), static_cast<double>(hi)};
    });
}

ValueRange SparseVolume::normalisationRange() const {
    const std::optional<ValueRange> fixed = fixedNormalisationRange(type, range);
    return fixed ? *fixed : dataRange();
}

SparseVolume SparseVolume::fromDense(const Volume& dense) {
    SparseVolume v = dispatchVoxelType(dense.type, [&](auto t) {
        using T = decltype(t);
        const T* data = dense.data<T>();
        const glm::ivec3 bricks = bricksOf(dense.dims);
        const std::vector<std::uint8_t> all(static_cast<std::size_t>(bricks.x) * bricks.y * bricks.z, 1);
        return fromVoxels<T>(dense.dims, T(0), all, [&] {
            return [&](int x, int y, int z) { return data[dense.index(x, y, z)]; };
        });
    });
    v.spacing = dense.spacing;
    v.origin = dense.origin;
    v.range = dense.range;
    return v;
}

}  // namespace vri
