// OccupancyGrid::emptyDistances() and stencilDistances(): each brick's Chebyshev distance in bricks to the
// is not empty, against a search over all bricks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include <glm/vector_relational.hpp>

#include "vri/core/occupancy_grid.h"

using namespace vri;

TEST_CASE("the empty-space distances are the Chebyshev distances to the nearest visible brick, capped") {
    // 150x90x70 voxels (19x12x9 bricks, none a multiple of 8), invisible but for three single voxels,
    // so that distances range from 0 to past the cap along x.
    Volume v(glm::ivec3(150, 90, 70), VoxelType::UInt8);
    for (const glm::ivec3 p : {glm::ivec3(3, 4, 5), glm::ivec3(60, 85, 30), glm::ivec3(66, 40, 69)})
        v.data<std::uint8_t>()[v.index(p.x, p.y, p.z)] = 200;
    const TransferFunction tf({{0.0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1}},
                              EmissionModel::ColourTimesExtinction);
    const OccupancyGrid grid(v, GridConvention::CellCentred, tf);
    const glm::ivec3 b = grid.bricks();
    const auto& empty = grid.emptyFlags();
    const auto& distance = grid.emptyDistances();
    REQUIRE(distance.size() == empty.size());
    const auto at = [&](int x, int y, int z) { return (static_cast<std::size_t>(z) * b.y + y) * b.x + x; };
    int largest = 0;
    for (int z = 0; z < b.z; ++z)
        for (int y = 0; y < b.y; ++y)
            for (int x = 0; x < b.x; ++x) {
                int nearest = OccupancyGrid::kMaxDistance;
                for (int zz = 0; zz < b.z; ++zz)
                    for (int yy = 0; yy < b.y; ++yy)
                        for (int xx = 0; xx < b.x; ++xx)
                            if (!empty[at(xx, yy, zz)])
                                nearest = std::min(nearest, std::max({std::abs(x - xx), std::abs(y - yy),
                                                                      std::abs(z - zz)}));
                INFO(x, " ", y, " ", z);
                CHECK(distance[at(x, y, z)] == nearest);
                largest = std::max(largest, nearest);
            }
    CHECK(largest >= 8);  // not a small test
    CHECK(std::count(empty.begin(), empty.end(), 0) >= 3);
    // Without a visible brick, every brick is at the cap.
    const OccupancyGrid none(v, GridConvention::CellCentred,
                             TransferFunction({{0.0, 0, 0, 0, 0}, {1.0, 0, 0, 0, 0}}, EmissionModel::Colour));
    CHECK(std::all_of(none.emptyDistances().begin(), none.emptyDistances().end(),
                      [](std::int32_t d) { return d == OccupancyGrid::kMaxDistance; }));
}

TEST_CASE("the stencil bricks hold the stencils by their lowest voxel, without a margin; distances per octant") {
    // Three visible voxels in invisible ones: stencil brick m of an axis is visible exactly when one of
    // them lies in [4 m, 4 m + 4] along every axis (a voxel on a face shows in two bricks' stencils),
    // and in each octant of directions a brick's distance is the Chebyshev distance to the nearest
    // visible brick at or ahead of it along every axis, capped.
    Volume v(glm::ivec3(150, 90, 70), VoxelType::UInt8);
    const std::vector<glm::ivec3> visible = {glm::ivec3(3, 4, 5), glm::ivec3(60, 84, 30), glm::ivec3(66, 40, 69)};
    for (const glm::ivec3 p : visible)
        v.data<std::uint8_t>()[v.index(p.x, p.y, p.z)] = 200;
    const TransferFunction tf({{0.0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1}},
                              EmissionModel::ColourTimesExtinction);
    const OccupancyGrid grid(v, GridConvention::CellCentred, tf);
    const glm::ivec3 b = grid.stencilBricks();
    REQUIRE(b == glm::ivec3(38, 23, 18));
    const std::size_t count = static_cast<std::size_t>(b.x) * b.y * b.z;
    const auto& distance = grid.stencilDistances();
    REQUIRE(distance.size() == 8 * count + 3);  // 3 bytes of padding
    std::vector<glm::ivec3> shown;  // the visible bricks, by brute force
    for (int z = 0; z < b.z; ++z)
        for (int y = 0; y < b.y; ++y)
            for (int x = 0; x < b.x; ++x)
                for (const glm::ivec3 p : visible)
                    if (glm::all(glm::lessThanEqual(4 * glm::ivec3(x, y, z), p)) &&
                        glm::all(glm::lessThanEqual(p, 4 * glm::ivec3(x, y, z) + 4)))
                        shown.push_back(glm::ivec3(x, y, z));
    CHECK(shown.size() == 2 + 4 + 2);  // y = 4, 40, 84 and x = 60 lie on faces between two bricks
    int largest = 0, capped = 0;
    for (int octant = 0; octant < 8; ++octant) {
        const glm::ivec3 ahead(octant & 1 ? -1 : 1, octant & 2 ? -1 : 1, octant & 4 ? -1 : 1);
        for (int z = 0; z < b.z; ++z)
            for (int y = 0; y < b.y; ++y)
                for (int x = 0; x < b.x; ++x) {
                    const glm::ivec3 p(x, y, z);
                    int nearest = OccupancyGrid::kMaxStencilDistance;
                    for (const glm::ivec3 s : shown)
                        if (glm::all(glm::greaterThanEqual((s - p) * ahead, glm::ivec3(0))))
                            nearest = std::min(nearest, std::max({std::abs(x - s.x), std::abs(y - s.y),
                                                                  std::abs(z - s.z)}));
                    INFO("octant ", octant, " brick ", x, " ", y, " ", z);
                    CHECK(distance[octant * count + (static_cast<std::size_t>(z) * b.y + y) * b.x + x] == nearest);
                    largest = std::max(largest, nearest < OccupancyGrid::kMaxStencilDistance ? nearest : 0);
                    capped += nearest == OccupancyGrid::kMaxStencilDistance;
                }
    }
    CHECK(largest >= 16);  // not a small test: long distances below the cap, and bricks at the cap
    CHECK(capped > 0);
}
