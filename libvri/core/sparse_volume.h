#pragma once
// A volume kept as the 8^3 bricks that hold anything but a background value: the memory of a mostly empty
// scene grows with its occupied bricks, not with its box (plus a 4-byte table entry per brick of the box,
// 1/128 of a dense uint8 copy). Like OpenVDB's leaf nodes, and read from them (io/vdb/vdb_grids.cpp).
//
// Brick b holds voxels [8 b, 8 b + 8) along each axis. It is stored as a block of 9^3 voxels, x fastest:
// the brick and a one-voxel apron on its high sides, a copy of the first voxels of the next bricks. The
// trilinear stencil of a cell whose lower corner lies in brick b (voxels i and i + 1 along each axis)
// therefore lies in b's block, and the sampler (sparse_sampler.h) reads the same eight values the dense
// GridSampler reads, with the same arithmetic: images are bitwise those of the dense volume. A brick is
// stored when any voxel of its block differs from the background (bit for bit: -0.0 is stored); every
// other brick points to block 0, all background. Voxels outside stored bricks hold the background: a
// VDB's background value, 0 for a dense input.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <tbb/parallel_for.h>

#include "libvri/core/volume.h"
#include "libvri/core/voxel_type.h"

namespace vri {

class SparseVolume {
public:
    static constexpr int kBrickShift = 3;
    static constexpr int kBrick = 1 << kBrickShift;  // voxels per brick edge
    static constexpr int kBlock = kBrick + 1;        // voxels per stored block edge: the brick and its apron
    static constexpr int kBlockVoxels = kBlock * kBlock * kBlock;

    SparseVolume() = default;

    // The volume whose voxels `makeReader()()` gives: a reader r, made once per parallel task, returns
    // r(x, y, z) as a T for any voxel inside dims. Only the bricks whose flag in `candidates` (one per
    // brick, x fastest) is set are read; the others must hold the background throughout. Throws vri::Error
    // when a dimension is < 1 or the table or the blocks would exceed byteLimit() (checked_size.h), which
    // is checked before they are allocated.
    template <class T, class MakeReader>
    static SparseVolume fromVoxels(glm::ivec3 dims, T background, const std::vector<std::uint8_t>& candidates,
                                   const MakeReader& makeReader);
    // The bricks of a dense volume that are not all 0 (its spacing, origin and range kept).
    static SparseVolume fromDense(const Volume& dense);

    glm::ivec3 dims{0, 0, 0};
    glm::dvec3 spacing{1.0, 1.0, 1.0};  // as Volume
    glm::dvec3 origin{0.0, 0.0, 0.0};
    VoxelType type = VoxelType::UInt8;
    std::optional<ValueRange> range;

    double background() const { return background_; }
    glm::ivec3 bricks() const { return bricks_; }
    static glm::ivec3 bricksOf(glm::ivec3 dims) { return (dims - 1) / kBrick + 1; }  // for dims >= 1
    std::size_t brickCount() const { return table_.size(); }
    std::size_t storedBricks() const { return blocks_ - 1; }  // block 0, the background, not counted
    std::size_t voxelCount() const;                           // of the box, as Volume::voxelCount()
    std::size_t byteCount() const { return table_.size() * sizeof(std::uint32_t) + voxels_.size(); }
    std::size_t brickIndex(int bx, int by, int bz) const {
        return (static_cast<std::size_t>(bz) * bricks_.y + by) * bricks_.x + bx;
    }
    // The stored block of brick `brick` (brickIndex), 9^3 voxels x fastest.
    template <class T> const T* block(std::size_t brick) const {
        return reinterpret_cast<const T*>(voxels_.data()) + std::size_t(table_[brick]) * kBlockVoxels;
    }
    // The table and the blocks, for the sampler.
    const std::uint32_t* table() const { return table_.data(); }
    template <class T> const T* blocks() const { return reinterpret_cast<const T*>(voxels_.data()); }

    double value(int x, int y, int z) const;  // any type, as double; no bounds check
    ValueRange dataRange() const;             // min..max over all voxels of the box, as Volume::dataRange()
    ValueRange normalisationRange() const;    // as Volume::normalisationRange()
    // Calls f(brick, x0, y0, z0, nx, ny, nz) for each stored brick: its index and the box of its own
    // voxels (not the apron) inside dims. In parallel.
    template <class F> void forEachStoredBrick(const F& f) const;

private:
    SparseVolume(glm::ivec3 dims, VoxelType type, double background);  // all background
    template <class T> T* writableBlock(std::size_t block) {
        return reinterpret_cast<T*>(voxels_.data()) + block * kBlockVoxels;
    }
    void allocateBlocks(std::size_t blocks);  // checked against byteLimit(); block 0 filled by the caller

    double background_ = 0.0;
    glm::ivec3 bricks_{0, 0, 0};
    std::vector<std::uint32_t> table_;  // per brick, x fastest: its block; 0 for the background block
    std::size_t blocks_ = 1;
    std::vector<std::byte> voxels_;  // blocks_ blocks of kBlockVoxels voxels of `type`
};

template <class T, class MakeReader>
SparseVolume SparseVolume::fromVoxels(glm::ivec3 dims, T background, const std::vector<std::uint8_t>& candidates,
                                      const MakeReader& makeReader) {
    SparseVolume v(dims, voxelTypeOf<T>(), static_cast<double>(background));
    const auto sameBits = [](T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; };
    // Reads brick b's block into `out` (voxels beyond dims: background); true when any voxel is not it.
    const auto readBlock = [&](auto& read, std::size_t b, T* out) {
        const int bx = static_cast<int>(b % v.bricks_.x), by = static_cast<int>(b / v.bricks_.x % v.bricks_.y),
                  bz = static_cast<int>(b / v.bricks_.x / v.bricks_.y);
        bool any = false;
        for (int k = 0; k < kBlock; ++k)
            for (int j = 0; j < kBlock; ++j)
                for (int i = 0; i < kBlock; ++i) {
                    const int x = bx * kBrick + i, y = by * kBrick + j, z = bz * kBrick + k;
                    const bool inside = x < dims.x && y < dims.y && z < dims.z;
                    const T value = inside ? static_cast<T>(read(x, y, z)) : background;
                    out[(k * kBlock + j) * kBlock + i] = value;
                    any = any || !sameBits(value, background);
                }
        return any;
    };
    // Two passes over the candidates, each parallel: which bricks to keep, then their blocks, in brick order.
    std::vector<std::uint8_t> keep(v.table_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keep.size()), [&](const auto& r) {
        auto read = makeReader();
        T scratch[kBlockVoxels];
        for (std::size_t b = r.begin(); b < r.end(); ++b)
            if (candidates[b]) keep[b] = readBlock(read, b, scratch);
    });
    std::size_t blocks = 1;
    for (std::size_t b = 0; b < keep.size(); ++b)
        if (keep[b]) v.table_[b] = static_cast<std::uint32_t>(blocks++);
    v.allocateBlocks(blocks);
    std::fill_n(v.writableBlock<T>(0), kBlockVoxels, background);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keep.size()), [&](const auto& r) {
        auto read = makeReader();
        for (std::size_t b = r.begin(); b < r.end(); ++b)
            if (keep[b]) readBlock(read, b, v.writableBlock<T>(v.table_[b]));
    });
    return v;
}

template <class F>
void SparseVolume::forEachStoredBrick(const F& f) const {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, table_.size()), [&](const auto& r) {
        for (std::size_t b = r.begin(); b < r.end(); ++b) {
            if (table_[b] == 0) continue;
            const int x0 = static_cast<int>(b % bricks_.x) * kBrick, y0 = static_cast<int>(b / bricks_.x % bricks_.y) * kBrick,
                      z0 = static_cast<int>(b / bricks_.x / bricks_.y) * kBrick;
            f(b, x0, y0, z0, std::min(kBrick, dims.x - x0), std::min(kBrick, dims.y - y0), std::min(kBrick, dims.z - z0));
        }
    });
}

}  // namespace vri
