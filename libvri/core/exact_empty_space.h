#pragma once
// The exact method's empty space (exact_reference.cpp): where the transfer function leaves a volume's
// cells invisible, at three scales. A cell is invisible when the TF is zero (no extinction, and no
// emission that could show) on the whole range of its 8 corners: the trilinear interpolant is a convex
// combination of them, so a piece of ray in the cell adds exactly nothing and leaves the transparency
// exactly as it was. A block of 4^3 cells is empty when all its cells are, a region of 8^3 blocks
// (32^3 cells) when all its blocks are; the walk jumps over runs of empty regions and blocks and steps
// cell by cell only through the others, so skipping leaves every bit of the image and its bounds as they
// were. 4^3 blocks follow the bonsai's leaves and twigs closely; regions cross the air around them in
// a few steps. Built once per volume and transfer function and kept across frames (occupancy_cache.h).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/transfer_function.h"
#include "libvri/core/volume.h"

namespace vri {

class ExactEmptySpace {
public:
    static constexpr int kBlockShift = 2;   // cells per block edge: 4
    static constexpr int kRegionShift = 3;  // blocks per region edge: 8

    ExactEmptySpace(const Volume& volume, const TransferFunction& tf);

    // Whether the TF is zero on the normalised values of every raw value in [rawLo, rawHi]: for 8- and
    // 16-bit voxels from a table, the same answers as tf.isInvisible, faster.
    bool invisible(double rawLo, double rawHi) const {
        if (!invisibleUpTo_.empty()) return rawHi <= invisibleUpTo_[static_cast<std::size_t>(rawLo)];
        return tf_.isInvisible((rawLo - lo_) * invRange_, (rawHi - lo_) * invRange_);
    }

    // Blocks tile the cells by their base (lowest) corner: block m of an axis holds the cells with base
    // index [4 m, 4 m + 4), whose corners are the voxels [4 m, min(4 m + 4, n - 1)]; the first and last
    // blocks also own the clamped region outside the index range. Regions group 8 blocks the same way.
    glm::ivec3 blocks() const { return blocks_; }
    bool emptyBlock(const int m[3]) const { return emptyBlock_[index(m[0], m[1], m[2], blocks_)] != 0; }
    bool emptyRegionOf(const int m[3]) const {  // the region that holds block m
        return emptyRegion_[index(m[0] >> kRegionShift, m[1] >> kRegionShift, m[2] >> kRegionShift, regions_)] != 0;
    }

private:
    static std::size_t index(int x, int y, int z, const glm::ivec3& n) {
        return (static_cast<std::size_t>(z) * n.y + y) * n.x + x;
    }

    TransferFunction tf_;
    double lo_, invRange_;             // raw value to TF coordinate: (raw - lo) * invRange
    std::vector<int> invisibleUpTo_;   // 8- and 16-bit voxels: see the constructor
    glm::ivec3 blocks_, regions_;
    std::vector<std::uint8_t> emptyBlock_, emptyRegion_;  // x fastest, 1 when empty
};

}  // namespace vri
