#pragma once
// A volume cut into a grid of bricks, rendered one brick at a time (`--bricks`, `--brick`): the data-parallel
// split of renderers such as IceT or OSPRay's distributed frame buffer, for volumes larger than one machine's
// memory. (Not the 8^3 blocks of sparse_volume.h or occupancy_grid.h, which are storage and empty space.)
//
// Along axis a, brick b owns the samples whose continuous voxel index x (GridSamplerLayout::cell's, before
// clamping; voxel i sits at x = i) lies in [start(b), start(b + 1)), the first brick everything below and the
// last everything above: every sample of every ray belongs to exactly one brick. The samples stay those of
// the whole ray (t_k = t_0 + k h from the whole volume's entry), so a brick's samples are bitwise the whole
// render's; only the sums are split (brick_layers.h joins them).
//
// A brick reads the voxels [start(b), start(b + 1)] along each axis (clamped to the volume): a sample it
// owns has its cell's lower corner at start(b) .. start(b + 1) - 1 (the first brick's clamped to 0, the
// last's to the volume's last cell), so the one voxel past its own, its ghost layer, completes every cell.
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

namespace vri {

// Voxels [lo, hi) along each axis.
struct VoxelBox {
    glm::ivec3 lo{0}, hi{0};
    glm::ivec3 size() const { return hi - lo; }
    std::uint64_t voxelCount() const;
    bool operator==(const VoxelBox&) const = default;
};

class BrickGrid {
public:
    // The most bricks along one axis: a ray visits at most the sum of the three counts.
    static constexpr int kMaxPerAxis = 64;

    BrickGrid() = default;
    // Throws vri::Error when a count is below 1, above kMaxPerAxis or above the voxels along its axis.
    BrickGrid(glm::ivec3 dims, glm::ivec3 counts);

    glm::ivec3 dims() const { return dims_; }
    glm::ivec3 counts() const { return counts_; }
    int brickCount() const { return counts_.x * counts_.y * counts_.z; }
    // The first voxel of brick b along `axis`: floor(b dims / counts), so bricks differ by at most one voxel.
    int start(int axis, int b) const;
    // The brick along `axis` that owns continuous voxel index x.
    int brickAlong(int axis, double x) const;
    // The voxels a brick reads: its own and the ghost layer above them, clamped to the volume.
    VoxelBox storedBox(glm::ivec3 brick) const;
    // Throws vri::Error "<what>: brick I,J,K is not in the NX,NY,NZ grid" unless 0 <= brick < counts.
    void requireBrick(glm::ivec3 brick, const std::string& what) const;

    bool operator==(const BrickGrid&) const = default;

private:
    glm::ivec3 dims_{1}, counts_{1};
};

// "I,J,K".
std::string brickText(glm::ivec3 brick);

}  // namespace vri
