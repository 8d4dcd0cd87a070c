// StencilBricks (occupancy_grid.h): which bricks of stencils are empty, and per octant of ray directions each
// brick's Chebyshev distance to the nearest visible brick ahead, against a search over all bricks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include <glm/vector_relational.hpp>

#include "libvri/core/occupancy_grid.h"
#include "test_camera.h"

using namespace vri;

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
    StencilBricks grid(v, GridConvention::CellCentred, tf);
    CHECK(std::all_of(grid.distances().begin(), grid.distances().end(), [](std::uint8_t d) { return d == 0; }));
    grid.addOctants(0xFF);  // before: every octant "not empty", which skips nothing
    CHECK(grid.octants() == 0xFF);
    const glm::ivec3 b = grid.bricks();
    REQUIRE(b == glm::ivec3(38, 23, 18));
    const std::size_t count = static_cast<std::size_t>(b.x) * b.y * b.z;
    const auto& distance = grid.distances();
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
                    int nearest = StencilBricks::kMaxDistance;
                    for (const glm::ivec3 s : shown)
                        if (glm::all(glm::greaterThanEqual((s - p) * ahead, glm::ivec3(0))))
                            nearest = std::min(nearest, std::max({std::abs(x - s.x), std::abs(y - s.y),
                                                                  std::abs(z - s.z)}));
                    INFO("octant ", octant, " brick ", x, " ", y, " ", z);
                    CHECK(distance[octant * count + (static_cast<std::size_t>(z) * b.y + y) * b.x + x] == nearest);
                    largest = std::max(largest, nearest < StencilBricks::kMaxDistance ? nearest : 0);
                    capped += nearest == StencilBricks::kMaxDistance;
                }
    }
    CHECK(largest >= 16);  // not a small test: long distances below the cap, and bricks at the cap
    CHECK(capped > 0);
    // Without a visible brick, every brick is at the cap in every octant.
    StencilBricks none(v, GridConvention::CellCentred,
                       TransferFunction({{0.0, 0, 0, 0, 0}, {1.0, 0, 0, 0, 0}}, EmissionModel::Colour));
    none.addOctants(0xFF);
    CHECK(std::all_of(none.distances().begin(), none.distances().end() - 3,
                      [](std::uint8_t d) { return d == StencilBricks::kMaxDistance; }));
}

TEST_CASE("rayOctants: the octants of every pixel's direction, from the corners") {
    // Against every pixel's direction, for views along an axis (both signs across the image on two axes),
    // along a diagonal with a narrow field (one octant), and zoomed off-centre.
    std::vector<CameraSpec> views = {test::cameraSpec(glm::dvec3(0.0, 0.0, -50.0), glm::dvec3(0.0), 40.0, 31, 23),
                                     test::cameraSpec(glm::dvec3(40.0, 30.0, 20.0), glm::dvec3(0.0), 10.0, 31, 23),
                                     test::cameraSpec(glm::dvec3(-5.0, 60.0, 7.0), glm::dvec3(1.0, 2.0, 3.0), 70.0, 40, 9)};
    CameraSpec zoomed = views[0];
    zoomed.zoom = 4.0;
    zoomed.zoomCentre = glm::dvec2(3.0, 20.0);
    views.push_back(zoomed);
    std::vector<unsigned> found;
    for (const CameraSpec& spec : views) {
        const Camera camera(spec);
        unsigned all = 0;
        for (int py = 0; py < camera.height(); ++py)
            for (int px = 0; px < camera.width(); ++px) {
                const glm::dvec3 d = camera.direction(px, py);
                all |= 1u << ((d.x < 0.0) + 2 * (d.y < 0.0) + 4 * (d.z < 0.0));
            }
        CHECK(rayOctants(camera) == all);
        found.push_back(all);
    }
    CHECK(found[0] == 0b1111);  // looking down +z from the axis: x and y take both signs
    CHECK(found[1] == 0b1000'0000);  // looking at the origin from (40, 30, 20): every component < 0
}
