#pragma once
// One brick of a dense volume (brick_grid.h): the voxels of its stored box, with the whole volume's shape,
// spacing, origin and normalisation range, from which every sample's addressing and scalar are computed, so
// that the brick's samples are bitwise the whole volume's. Its memory is the stored box's.
#include <memory>

#include <glm/vec3.hpp>

#include "libvri/core/brick_grid.h"
#include "libvri/core/volume.h"

namespace vri {

struct BrickVolume {
    BrickGrid grid;
    glm::ivec3 brick{0};  // which brick of the grid
    // The voxels of its stored box, with the whole volume's spacing, origin and normalisation range (always
    // set: a brick's own min..max would move a float volume's scalars); the box they stand in is the whole's.
    Volume voxels;

    glm::ivec3 dims() const { return grid.dims(); }  // the whole volume's
    VoxelBox stored() const { return grid.storedBox(brick); }
};

// The brick of an in-memory volume (a copy of its stored box): for volumes no reader cuts while reading.
BrickVolume cutBrick(const Volume& whole, const BrickGrid& grid, glm::ivec3 brick);

}  // namespace vri
