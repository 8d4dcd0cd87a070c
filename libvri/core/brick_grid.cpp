#include "libvri/core/brick_grid.h"

#include <algorithm>

#include "libvri/util/error.h"

namespace vri {

std::uint64_t VoxelBox::voxelCount() const {
    const glm::ivec3 s = size();
    return static_cast<std::uint64_t>(s.x) * static_cast<std::uint64_t>(s.y) * static_cast<std::uint64_t>(s.z);
}

BrickGrid::BrickGrid(glm::ivec3 dims, glm::ivec3 counts) : dims_(dims), counts_(counts) {
    const char* axes = "xyz";
    for (int a = 0; a < 3; ++a) {
        if (dims[a] < 1) throw Error(std::string("--bricks: the volume has no voxels along ") + axes[a]);
        if (counts[a] < 1 || counts[a] > kMaxPerAxis || counts[a] > dims[a])
            throw Error(std::string("--bricks: expected 1 to ") + std::to_string(std::min(kMaxPerAxis, dims[a])) +
                        " bricks along " + axes[a] + " (the volume has " + std::to_string(dims[a]) +
                        " voxels there), got " + std::to_string(counts[a]));
    }
}

int BrickGrid::start(int axis, int b) const {
    return static_cast<int>(static_cast<std::int64_t>(b) * dims_[axis] / counts_[axis]);
}

int BrickGrid::brickAlong(int axis, double x) const {
    // The planes start(1) .. start(n - 1) increase with b: the owner is the number of planes at or below x.
    int lo = 0, hi = counts_[axis] - 1;
    while (lo < hi) {
        const int mid = (lo + hi + 1) / 2;
        if (static_cast<double>(start(axis, mid)) <= x)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

VoxelBox BrickGrid::storedBox(glm::ivec3 brick) const {
    VoxelBox box;
    for (int a = 0; a < 3; ++a) {
        box.lo[a] = start(a, brick[a]);
        box.hi[a] = std::min(start(a, brick[a] + 1) + 1, dims_[a]);
    }
    return box;
}

void BrickGrid::requireBrick(glm::ivec3 brick, const std::string& what) const {
    for (int a = 0; a < 3; ++a)
        if (brick[a] < 0 || brick[a] >= counts_[a])
            throw Error(what + ": brick " + brickText(brick) + " is not in the " + brickText(counts_) +
                        " grid (expected 0 <= I,J,K < the counts)");
}

std::string brickText(glm::ivec3 brick) {
    return std::to_string(brick.x) + "," + std::to_string(brick.y) + "," + std::to_string(brick.z);
}

}  // namespace vri
