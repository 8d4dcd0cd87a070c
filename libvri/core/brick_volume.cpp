#include "libvri/core/brick_volume.h"

#include <cstring>

#include "libvri/util/error.h"

namespace vri {

BrickVolume cutBrick(const Volume& whole, const BrickGrid& grid, glm::ivec3 brick) {
    if (grid.dims() != whole.dims) throw Error("bricks: the grid was made for another volume's dimensions");
    grid.requireBrick(brick, "--brick");
    const VoxelBox stored = grid.storedBox(brick);
    BrickVolume b{grid, brick, Volume(stored.size(), whole.type)};
    b.voxels.spacing = whole.spacing;
    b.voxels.origin = whole.origin;
    b.voxels.range = whole.normalisationRange();
    const std::size_t size = voxelSize(whole.type);
    const std::size_t rowBytes = static_cast<std::size_t>(stored.size().x) * size;
    for (int z = stored.lo.z; z < stored.hi.z; ++z)
        for (int y = stored.lo.y; y < stored.hi.y; ++y)
            std::memcpy(b.voxels.bytes.data() + b.voxels.index(0, y - stored.lo.y, z - stored.lo.z) * size,
                        whole.bytes.data() + whole.index(stored.lo.x, y, z) * size, rowBytes);
    return b;
}

}  // namespace vri
