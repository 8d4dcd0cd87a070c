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
    VoxelBox stored;      // grid.storedBox(brick)
    // The stored box's voxels (dims = stored.size()); `range` always set: the whole volume's normalisation
    // range, since a brick's own min..max would move a float volume's scalars.
    Volume voxels;
    glm::ivec3 dims{0};  // the whole volume's
    glm::dvec3 spacing{1.0}, origin{0.0};
};

// The brick of an in-memory volume (a copy of its stored box): for volumes no reader cuts while reading.
BrickVolume cutBrick(const Volume& whole, const BrickGrid& grid, glm::ivec3 brick);

}  // namespace vri
