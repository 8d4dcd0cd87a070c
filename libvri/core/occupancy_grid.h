#pragma once
// Empty-space skipping that cannot change a result: bricks of the volume over which the transfer
// function has neither emission nor extinction. A sample there adds exactly 0 to the colour and
// multiplies the transparency by exactly exp(0) = 1, so skipping it leaves every bit of the image
// as it was. The test that a brick is empty is conservative: it looks at the brick's voxels plus a
// one-voxel margin (more than the trilinear stencil needs) and widens the scalar range slightly, so
// rounding in sample positions or in a float sampler cannot make it wrong.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/camera.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/core/transfer_function.h"
#include "libvri/core/volume.h"

namespace vri {

class OccupancyGrid {
public:
    static constexpr int kBrickShift = 3;
    static constexpr int kBrick = 1 << kBrickShift;  // voxels per brick edge

    OccupancyGrid(const Volume& volume, GridConvention convention, const TransferFunction& tf);
    // The bricks where every lookup of a pre-integration table is exactly 0 (PreintegrationTable::isInvisible),
    // for the segments of --method preintegrated.
    OccupancyGrid(const Volume& volume, GridConvention convention, const PreintegrationTable& table);
    // The same grid, bit for bit, from the stored bricks alone: a brick and its margin in no stored
    // brick's block hold the background only.
    OccupancyGrid(const SparseVolume& volume, GridConvention convention, const TransferFunction& tf);

    // An index-space ray x0 + t * dxdt, with what visit() needs precomputed once per ray.
    struct Ray {
        Ray(const glm::dvec3& x0, const glm::dvec3& dxdt) : x0(x0), dxdt(dxdt), invD(1.0 / dxdt) {}
        glm::dvec3 x0, dxdt, invD;
    };

    // The brick that holds the ray's point at parameter t, whether it is empty, and the parameter
    // where the ray leaves it. The exit may be off by rounding: the one-voxel margin of the emptiness
    // test covers samples that sit a rounding error beyond the brick.
    struct Visit {
        bool empty;
        double tExit;
    };
    Visit visit(const Ray& ray, double t) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        std::size_t cell = 0;
        double tExit = inf;
        for (int a = 2; a >= 0; --a) {
            const double x = std::clamp(ray.x0[a] + t * ray.dxdt[a], 0.0, maxIndex_[a]);
            const int m = std::min(static_cast<int>(x) >> kBrickShift, bricks_[a] - 1);
            cell = cell * static_cast<std::size_t>(bricks_[a]) + static_cast<std::size_t>(m);
            // The first and last bricks also own the clamped region outside the voxel index range.
            if (ray.dxdt[a] > 0 && m + 1 < bricks_[a])
                tExit = std::min(tExit, ((m + 1) * kBrick - ray.x0[a]) * ray.invD[a]);
            else if (ray.dxdt[a] < 0 && m > 0)
                tExit = std::min(tExit, (m * kBrick - ray.x0[a]) * ray.invD[a]);
        }
        return {empty_[cell] != 0, tExit};
    }

    glm::ivec3 bricks() const { return bricks_; }
    glm::dvec3 maxIndex() const { return maxIndex_; }
    // Per brick, x fastest, 1 when empty: what visit() reads, for the Vulkan backend to upload.
    const std::vector<std::uint8_t>& emptyFlags() const { return empty_; }
    double emptyFraction() const;

private:
    explicit OccupancyGrid(glm::ivec3 dims);  // the bricks of dims, none marked empty

    glm::ivec3 dims_;
    glm::dvec3 maxIndex_;  // dims - 1
    glm::ivec3 bricks_;
    std::vector<std::uint8_t> empty_;
};

// The packet engine's empty space (simd_march.cpp), finer than OccupancyGrid's bricks: the engine
// knows the trilinear stencil of every sample it evaluates, so brick m of an axis holds the stencils
// whose lowest voxel lies in [4 m, 4 m + 4), and is empty when the TF gives nothing to the voxels
// [4 m, 4 m + 4], without OccupancyGrid's margin, which covers the scalar walk's positions (a stencil
// is tested as it is evaluated; the value's rounding is padded as there). On Bonsai 64 % of the
// samples that the 8^3 bricks let through have no extinction; these bricks let a third fewer through.
// A ray only goes forward, so what lies behind it does not limit its jumps: the distances are kept
// per octant of directions, octant o = [x < 0] + 2 [y < 0] + 4 [z < 0] of the ray's direction, as the
// Chebyshev distance to the nearest non-empty brick among those at or ahead of it along every axis
// (index >= along an axis the octant goes up, <= down), up to kMaxDistance bricks (0 for a brick that
// is not empty): every brick from this one to d - 1 bricks ahead along each axis is empty, so a ray
// there can jump to the faces of that box at once. Built only for the packet engine, and only in the
// octants a camera's rays take (a view holds one to four of the eight), kept across frames like the
// grid (occupancy_cache.h); dense volumes only, as the engine.
class StencilBricks {
public:
    static constexpr int kShift = 2;                 // voxels per brick edge: 4
    static constexpr std::int32_t kMaxDistance = 32;  // 128 voxels

    // The empty bricks; no octant's distances yet.
    StencilBricks(const Volume& volume, GridConvention convention, const TransferFunction& tf);
    // Pre-integration's: a brick is empty where the table's lookups between any two of its scalars are
    // exactly 0 (PreintegrationTable::isInvisible). The ends of a segment one step apart, a step shorter than
    // a brick along every axis, lie in one brick or in two that touch, whose voxel ranges share voxels: two
    // such ranges lie in one run of zero entries, and the segment's lookup is 0 too.
    StencilBricks(const Volume& volume, GridConvention convention, const PreintegrationTable& table);

    // Builds the distances of the octants in `octants` (bit o for octant o) not built yet.
    void addOctants(unsigned octants);
    unsigned octants() const { return octants_; }

    glm::ivec3 bricks() const { return bricks_; }
    // A byte per brick (a quarter of the cache that words would take): octant o's bricks at
    // [o N, (o + 1) N), N = the brick count, x fastest, then 3 bytes of padding so that a 32-bit load
    // at any brick stays inside. An octant not built holds 0s, "not empty": it skips nothing.
    const std::vector<std::uint8_t>& distances() const { return distance_; }

private:
    void findEmpty(const Volume& volume, const std::function<bool(double, double)>& invisible);

    glm::ivec3 bricks_;
    std::vector<std::uint8_t> empty_;
    unsigned octants_ = 0;
    std::vector<std::uint8_t> distance_;
};

// The octants (StencilBricks) of the directions of a camera's rays: bit o for octant o = [x < 0] +
// 2 [y < 0] + 4 [z < 0]. A component of the direction through a pixel is an affine function of the
// pixel's position before normalisation, so its signs over the image are those at the corner pixels.
// (A ray whose direction rounds to another octant, next to a sign change, reads an octant not built:
// it skips nothing there, and its image is the same.)
unsigned rayOctants(const Camera& camera);

}  // namespace vri
