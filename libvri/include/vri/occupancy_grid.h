#pragma once
// Empty-space skipping that cannot change a result: bricks of the volume over which the transfer
// function has neither emission nor extinction. A sample there adds exactly 0 to the colour and
// multiplies the transparency by exactly exp(0) = 1, so skipping it leaves every bit of the image
// as it was. The test that a brick is empty is conservative: it looks at the brick's voxels plus a
// one-voxel margin (more than the trilinear stencil needs) and widens the scalar range slightly, so
// rounding in sample positions or in a float sampler cannot make it wrong.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "vri/grid_convention.h"
#include "vri/transfer_function.h"
#include "vri/volume.h"

namespace vri {

class OccupancyGrid {
public:
    static constexpr int kBrick = 8;  // voxels per brick edge

    OccupancyGrid(const Volume& volume, GridConvention convention, const TransferFunction& tf);

    // The brick that holds the sample at parameter t of the index-space ray x0 + t * dxdt,
    // whether it is empty, and the parameter where the ray leaves it.
    struct Visit {
        bool empty;
        double tExit;
    };
    Visit visit(const glm::dvec3& x0, const glm::dvec3& dxdt, double t) const;

    glm::ivec3 bricks() const { return bricks_; }
    double emptyFraction() const;

private:
    glm::ivec3 dims_;
    glm::ivec3 bricks_;
    std::vector<std::uint8_t> empty_;
};

}  // namespace vri
