#pragma once
// A summary of a volume's values: what `vri-convert --info` prints, and what a transfer function
// designer wants to see before choosing control points.
#include <cstdint>
#include <vector>

#include "libvri/core/sparse_volume.h"
#include "libvri/core/volume.h"

namespace vri {

struct VolumeStats {
    ValueRange data;           // min..max over all voxels
    ValueRange normalisation;  // the raw values that s = 0..1 spans, Volume::normalisationRange()
    double mean = 0.0;
    double zeroFraction = 0.0;  // voxels equal to 0, i.e. empty space under most transfer functions
    // What a sparse copy needs: the voxels other than 0 (those a .vdb stores), and the bricks of
    // kStatsBrickSize^3 voxels (OpenVDB's leaf nodes, aligned to voxel 0) holding at least one of them.
    std::uint64_t activeVoxels = 0;
    std::uint64_t bricks = 0;
    std::uint64_t activeBricks = 0;
    // Equal-width bins over the normalisation range (its hi value falls in the last bin), and the
    // voxels outside it, NaN counted as below.
    std::vector<std::uint64_t> histogram;
    std::uint64_t below = 0;
    std::uint64_t above = 0;
};

inline constexpr int kStatsBrickSize = 8;

// Throws vri::Error when bins < 1.
VolumeStats computeVolumeStats(const Volume& volume, int bins = 16);
// The same from the stored bricks alone (the background counted once for all other voxels); equal to the
// dense volume's stats but for the mean's rounding (the sum runs brick by brick).
VolumeStats computeVolumeStats(const SparseVolume& volume, int bins = 16);

}  // namespace vri
