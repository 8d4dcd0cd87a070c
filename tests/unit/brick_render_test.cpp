// Bricks (issue 49): the grid's planes and stored boxes, the sampler reading a brick's voxels as the whole
// volume's, every sample of every ray in exactly one brick, and the layers joined into the whole render's
// image within brick_layers.h's bound, the same bits whatever order the layers come in.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include <glm/geometric.hpp>

#include "same_bits.h"
#include "test_camera.h"
#include "libvri/core/brick_layers.h"
#include "libvri/core/brick_sampler.h"
#include "libvri/core/brick_volume.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

std::shared_ptr<Volume> noise(glm::ivec3 dims, VoxelType type, unsigned seed) {
    auto v = std::make_shared<Volume>(dims, type);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (std::size_t i = 0; i < v->voxelCount(); ++i)
        dispatchVoxelType(type, [&](auto t) {
            using T = decltype(t);
            v->data<T>()[i] = static_cast<T>(std::is_same_v<T, float> ? 3.0 * u01(rng) - 1.0 : 255.0 * u01(rng));
        });
    return v;
}

TransferFunction ramp() {
    return TransferFunction({{0.0, 0.0, 0.0, 0.0, 0.0}, {0.3, 0.8, 0.5, 0.2, 0.4}, {1.0, 0.9, 0.3, 0.1, 3.0}},
                            EmissionModel::ColourTimesExtinction);
}

// The layers of every brick of `counts`, joined.
BrickComposite joined(const Volume& whole, glm::ivec3 counts, const Scene& like, const Camera& camera,
                      const RenderOptions& options, bool reversed = false) {
    const BrickGrid grid(whole.dims, counts);
    std::vector<Image> layers;
    std::vector<std::string> names;
    for (int z = 0; z < counts.z; ++z)
        for (int y = 0; y < counts.y; ++y)
            for (int x = 0; x < counts.x; ++x) {
                Scene scene = like;
                scene.volume = nullptr;
                scene.brick = std::make_shared<BrickVolume>(cutBrick(whole, grid, {x, y, z}));
                layers.push_back(render(scene, camera, options));
                names.push_back(brickText({x, y, z}));
            }
    if (reversed) {
        std::reverse(layers.begin(), layers.end());
        std::reverse(names.begin(), names.end());
    }
    std::vector<const Image*> pointers;
    for (const Image& l : layers) pointers.push_back(&l);
    return compositeBrickLayers(pointers, names,
                                maxSamplesPerRay(glm::length(glm::dvec3(whole.dims)), options.samplingRate));
}

double largestDifference(const Image& a, const Image& b) {
    REQUIRE(a.pixels.size() == b.pixels.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        worst = std::max(worst, std::abs(static_cast<double>(a.pixels[i]) - b.pixels[i]));
    return worst;
}

}  // namespace

TEST_CASE("a brick grid splits each axis into bricks a voxel apart at most and stores a ghost voxel above") {
    const BrickGrid grid({10, 7, 1}, {3, 2, 1});
    CHECK(grid.start(0, 0) == 0);
    CHECK(grid.start(0, 1) == 3);
    CHECK(grid.start(0, 2) == 6);
    CHECK(grid.start(0, 3) == 10);
    CHECK(grid.brickAlong(0, -0.5) == 0);
    CHECK(grid.brickAlong(0, 2.999) == 0);
    CHECK(grid.brickAlong(0, 3.0) == 1);
    CHECK(grid.brickAlong(0, 9.5) == 2);
    CHECK(grid.brickAlong(1, 2.999) == 0);
    CHECK(grid.brickAlong(1, 3.0) == 1);
    CHECK(grid.storedBox({0, 0, 0}) == VoxelBox{{0, 0, 0}, {4, 4, 1}});
    CHECK(grid.storedBox({1, 1, 0}) == VoxelBox{{3, 3, 0}, {7, 7, 1}});
    CHECK(grid.storedBox({2, 1, 0}) == VoxelBox{{6, 3, 0}, {10, 7, 1}});
    CHECK_THROWS_WITH_AS(BrickGrid({10, 7, 1}, {3, 2, 2}),
                         "--bricks: expected 1 to 1 bricks along z (the volume has 1 voxels there), got 2", Error);
    CHECK_THROWS_WITH_AS(grid.requireBrick({3, 0, 0}, "--brick"),
                         "--brick: brick 3,0,0 is not in the 3,2,1 grid (expected 0 <= I,J,K < the counts)", Error);
}

TEST_CASE("a brick's sampler reads the whole volume's scalar at every point the brick owns") {
    const auto whole = noise({13, 9, 11}, VoxelType::UInt16, 5);
    const BrickGrid grid(whole->dims, {3, 2, 2});
    for (const GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred}) {
        const GridSampler<std::uint16_t, double> reference(*whole, convention);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-0.05, 1.05);
        for (int i = 0; i < 5000; ++i) {
            const glm::dvec3 p(u(rng), u(rng), u(rng));
            const glm::dvec3 x = reference.index(p);
            const glm::ivec3 owner{grid.brickAlong(0, x.x), grid.brickAlong(1, x.y), grid.brickAlong(2, x.z)};
            const BrickVolume brick = cutBrick(*whole, grid, owner);
            const BrickGridSampler<std::uint16_t, double> sampler(brick, convention);
            const double a = reference(p), b = sampler(p);
            REQUIRE(std::memcmp(&a, &b, sizeof a) == 0);
        }
    }
}

TEST_CASE("every sample of a ray lies in exactly one brick, the bricks' runs in the order of their places") {
    const BrickGrid grid({20, 20, 20}, {4, 3, 2});
    const GridSamplerLayout<double> layout({20, 20, 20}, ValueRange{0, 1}, GridConvention::CellCentred);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int ray = 0; ray < 300; ++ray) {
        glm::dvec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        if (ray % 3 == 0) b.y = a.y = std::floor(a.y * 20) / 20 + 0.5 / 20;  // along a plane of voxel centres
        if (ray % 5 == 0) b.x = a.x;                                         // parallel to the x planes
        const std::int64_t count = 137;
        const glm::dvec3 du = (b - a) / static_cast<double>(count);
        const auto position = [&](std::int64_t k) { return a + static_cast<double>(k) * du; };
        std::vector<int> owner(count, -1), place(count, 0);
        for (int z = 0; z < 2; ++z)
            for (int y = 0; y < 3; ++y)
                for (int x = 0; x < 4; ++x) {
                    const BrickSamples run = brickSamples(grid, {x, y, z}, layout, du, count, position);
                    for (std::int64_t k = run.begin; k < run.end; ++k) {
                        REQUIRE(owner[k] == -1);
                        owner[k] = (z * 3 + y) * 4 + x;
                        place[k] = run.order;
                    }
                }
        for (std::int64_t k = 0; k < count; ++k) {
            REQUIRE(owner[k] >= 0);
            if (k > 0 && owner[k] != owner[k - 1]) REQUIRE(place[k] > place[k - 1]);
        }
    }
}

TEST_CASE("bricks joined give the whole render within the stated bound, the same bits in any order of layers") {
    const auto whole = noise({21, 17, 13}, VoxelType::UInt8, 3);
    const CameraSpec spec = test::cameraSpec(glm::dvec3(-20.0, 35.0, -40.0), glm::dvec3(10.5, 8.5, 6.5), 40.0, 37, 23);
    const Camera camera(spec);
    for (const Integrator integrator : {Integrator::Riemann, Integrator::Composite})
        for (const GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred})
            for (const bool jitter : {false, true}) {
                CAPTURE(integratorName(integrator));
                CAPTURE(jitter);
                RenderOptions options;
                options.integrator = integrator;
                options.samplingRate = 2.5;
                options.jitter = jitter;
                options.seed = 4;
                const Scene scene{whole, std::nullopt, convention, ramp()};
                const Image reference = render(scene, camera, options);
                for (const glm::ivec3 counts : {glm::ivec3(1, 1, 1), glm::ivec3(2, 2, 2), glm::ivec3(3, 1, 4)}) {
                    CAPTURE(brickText(counts));
                    const BrickComposite a = joined(*whole, counts, scene, camera, options);
                    CHECK(a.boundMax < 1e-5);
                    CHECK(largestDifference(a.image, reference) <= a.boundMax);
                    const BrickComposite b = joined(*whole, counts, scene, camera, options, true);
                    CHECK(test::sameBits(a.image, b.image));
                }
            }
}

TEST_CASE("a brick's layer of a region is that region of its whole layer, bit for bit") {
    const auto whole = noise({16, 12, 10}, VoxelType::Float32, 8);
    const Camera camera(test::cameraSpec(glm::dvec3(30.0, -25.0, 40.0), glm::dvec3(8, 6, 5), 35.0, 24, 18));
    Scene scene{nullptr, std::nullopt, GridConvention::CellCentred, ramp()};
    scene.brick = std::make_shared<BrickVolume>(cutBrick(*whole, BrickGrid(whole->dims, {2, 2, 1}), {1, 0, 0}));
    RenderOptions options;
    const Image all = render(scene, camera, options);
    options.region = PixelRegion{5, 3, 11, 9};
    const Image part = render(scene, camera, options);
    REQUIRE(part.channels == 5);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 11; ++x)
            for (int c = 0; c < 5; ++c) REQUIRE(part.at(x, y, c) == all.at(x + 5, y + 3, c));
}

TEST_CASE("a brick renders riemann and composite in double, without early termination, one frame") {
    const auto whole = noise({8, 8, 8}, VoxelType::UInt8, 1);
    Scene scene{nullptr, std::nullopt, GridConvention::CellCentred, ramp()};
    scene.brick = std::make_shared<BrickVolume>(cutBrick(*whole, BrickGrid(whole->dims, {2, 1, 1}), {0, 0, 0}));
    const Camera camera(test::cameraSpec(glm::dvec3(30.0, -25.0, 40.0), glm::dvec3(4), 35.0, 8, 6));
    RenderOptions options;
    options.integrator = Integrator::Coupled;
    CHECK_THROWS_WITH_AS(render(scene, camera, options),
                         "--brick: renders riemann and composite (a brick sums the fixed steps it owns), not coupled",
                         Error);
    options = {};
    options.precision = Precision::Float;
    CHECK_THROWS_AS(render(scene, camera, options), Error);
    options = {};
    options.earlyTermination = 0.01;
    CHECK_THROWS_AS(render(scene, camera, options), Error);
}
