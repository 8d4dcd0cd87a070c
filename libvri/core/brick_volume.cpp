#include "libvri/core/brick_volume.h"

#include <cstring>

#include "libvri/util/error.h"

namespace vri {

BrickVolume cutBrick(const Volume& whole, const BrickGrid& grid, glm::ivec3 brick) {
    if (grid.dims() != whole.dims) throw Error("bricks: the grid was made for another volume's dimensions");
    grid.requireBrick(brick, "--brick");
    BrickVolume b;
    b.grid = grid;
    b.brick = brick;
    b.stored = grid.storedBox(brick);
    b.dims = whole.dims;
    b.spacing = whole.spacing;
    b.origin = whole.origin;
    b.voxels = Volume(b.stored.size(), whole.type);
    b.voxels.spacing = whole.spacing;
    b.voxels.range = whole.normalisationRange();
    const std::size_t size = voxelSize(whole.type);
    const glm::ivec3 s = b.stored.size();
    const std::size_t rowBytes = static_cast<std::size_t>(s.x) * size;
    for (int z = 0; z < s.z; ++z)
        for (int y = 0; y < s.y; ++y)
            std::memcpy(b.voxels.bytes.data() + b.voxels.index(0, y, z) * size,
                        whole.bytes.data() + whole.index(b.stored.lo.x, b.stored.lo.y + y, b.stored.lo.z + z) * size,
                        rowBytes);
    return b;
}

}  // namespace vri
