// The packet engine (--simd on) against the scalar float path (--simd off): bitwise equal images and
// equal sample counts for every placement, integrator, voxel type, grid convention and emission
// model, with and without empty-space skipping, jittered or not, on odd image sizes (partly filled packets),
// on every Highway target this CPU runs, and on 1 and 2 threads.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <sys/mman.h>
#include <unistd.h>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>

#include <hwy/targets.h>
#include <tbb/global_control.h>

#include "same_bits.h"
#include "scoped_environment.h"
#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/core/simd_march.h"
#include "libvri/core/simd_target.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

// A 37x21x19 volume (no axis a multiple of the 8-voxel bricks): noise below s = 0.2 (invisible under
// the transfer functions below) around a ball of structure off to one side, so that rays cross empty
// bricks, visible bricks and both.
std::shared_ptr<Volume> testVolume(VoxelType type) {
    auto v = std::make_shared<Volume>(glm::ivec3(37, 21, 19), type);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(0.0, 1.0);
    for (int z = 0; z < 19; ++z)
        for (int y = 0; y < 21; ++y)
            for (int x = 0; x < 37; ++x) {
                const double r = std::hypot(x - 28.0, y - 10.0, z - 9.0);
                const double s = r < 7.5 ? 0.25 + 0.7 * noise(rng) : 0.15 * noise(rng);
                const std::size_t i = v->index(x, y, z);
                if (type == VoxelType::UInt8) v->data<std::uint8_t>()[i] = static_cast<std::uint8_t>(s * 255.0);
                if (type == VoxelType::UInt16) v->data<std::uint16_t>()[i] = static_cast<std::uint16_t>(s * 65535.0);
                if (type == VoxelType::Float32) v->data<float>()[i] = static_cast<float>(2.0 * s - 0.5);
            }
    if (type == VoxelType::Float32) v->range = ValueRange{-0.5, 1.5};
    return v;
}

// Zero below s = 0.2; `points` points in all (more than 17 makes the engine read the segments from
// memory instead of registers).
TransferFunction testTransferFunction(EmissionModel emission, int points) {
    std::vector<TransferFunctionPoint> p{{0.0, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}};
    for (int i = 0; i + 2 < points; ++i) {
        const double s = 0.2 + 0.8 * (i + 1) / (points - 2);
        p.push_back({s, 0.3 + 0.5 * s, 0.9 - 0.6 * s, 0.2 + 0.1 * (i % 3), 0.2 + 0.6 * s * (1 + i % 2)});
    }
    return TransferFunction(p, emission);
}

Camera testCamera(int width, int height) {
    const CameraSpec spec =
        test::cameraSpec(glm::dvec3(-30.0, 45.0, -50.0), glm::dvec3(18.5, 10.5, 9.5), 40.0, width, height);
    return Camera(spec);
}

}  // namespace

TEST_CASE("the packet engine's image equals the scalar float path's bit for bit on every target") {
    const Camera camera = testCamera(37, 23);  // neither a multiple of the 16-pixel tile nor of any lane count
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    int renders = 0;
    for (VoxelType type : {VoxelType::UInt8, VoxelType::UInt16, VoxelType::Float32})
        for (GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred})
            for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour})
                for (int points : {3, 9, 14, 24}) {  // 2, 8, 13, 23 segments: in one vector, two or memory
                    const Scene scene{testVolume(type), std::nullopt, convention,
                                      testTransferFunction(emission, points)};
                    for (Integrator integrator : {Integrator::Riemann, Integrator::Composite})
                        for (Placement placement : {Placement::EyeAlign, Placement::EntryAlign,
                                                    Placement::EntryExitAlign, Placement::EntryExitAlignCorner})
                            for (bool skip : {true, false}) {
                                RenderOptions opt;
                                opt.precision = Precision::Float;
                                opt.integrator = integrator;
                                opt.placement = placement;
                                opt.samplingRate = 2.7;
                                opt.skipEmptySpace = skip;
                                opt.simd = false;
                                RenderStats scalarStats;
                                const Image scalar = render(scene, camera, opt, &scalarStats);
                                CHECK(scalarStats.simdTarget.empty());
                                // Not a blank test: the rays see something, and cross empty bricks.
                                CHECK(*std::max_element(scalar.pixels.begin(), scalar.pixels.end()) > 0.05f);
                                CHECK((scalarStats.samplesEvaluated < scalarStats.samplesPlaced) == skip);
                                opt.simd = true;
                                for (std::int64_t target : targets) {
                                    hwy::SetSupportedTargetsForTest(target);
                                    RenderStats stats;
                                    const Image packets = render(scene, camera, opt, &stats);
                                    INFO(hwy::TargetName(target), " ", voxelTypeName(type), " ",
                                         gridConventionName(convention), " ", integratorName(integrator), " ",
                                         placementName(placement), " skip ", skip, " points ", points);
                                    CHECK(stats.simdTarget == hwy::TargetName(target));
                                    CHECK(test::sameBits(packets, scalar));
                                    CHECK(stats.samplesPlaced == scalarStats.samplesPlaced);
                                    // Skipping by finer bricks (StencilBricks, occupancy_grid.h), the
                                    // packets evaluate fewer samples (see the jumps' test below).
                                    if (skip)
                                        CHECK(stats.samplesEvaluated <= scalarStats.samplesEvaluated + 2);
                                    else
                                        CHECK(stats.samplesEvaluated == scalarStats.samplesEvaluated);
                                    CHECK(stats.raysHit == scalarStats.raysHit);
                                    ++renders;
                                }
                                hwy::SetSupportedTargetsForTest(0);
                            }
                }
    MESSAGE(renders, " packet renders on ", targets.size(), " targets");
}

TEST_CASE("jittered packets equal the jittered scalar float path bit for bit: every placement, seeds, frames") {
    const Camera camera = testCamera(37, 23);
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    const Scene scene{testVolume(VoxelType::UInt8), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    for (Integrator integrator : {Integrator::Riemann, Integrator::Composite})
        for (Placement placement :
             {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign, Placement::EntryExitAlignCorner})
            for (bool skip : {true, false})
                for (const auto& [seed, frames] : {std::pair{0u, 1}, std::pair{12345u, 1}, std::pair{7u, 3}}) {
                    RenderOptions opt;
                    opt.precision = Precision::Float;
                    opt.integrator = integrator;
                    opt.placement = placement;
                    opt.samplingRate = 1.3;  // a coarse step: the jitter moves samples visibly
                    opt.skipEmptySpace = skip;
                    opt.jitter = true;
                    opt.seed = seed;
                    opt.frames = frames;
                    opt.simd = false;
                    RenderStats scalarStats;
                    const Image scalar = render(scene, camera, opt, &scalarStats);
                    opt.jitter = false;  // not a blank test: the jitter changes the image
                    opt.frames = 1;
                    CHECK_FALSE(test::sameBits(render(scene, camera, opt), scalar));
                    opt.jitter = true;
                    opt.frames = frames;
                    opt.simd = true;
                    for (std::int64_t target : targets) {
                        hwy::SetSupportedTargetsForTest(target);
                        RenderStats stats;
                        const Image packets = render(scene, camera, opt, &stats);
                        INFO(hwy::TargetName(target), " ", integratorName(integrator), " ", placementName(placement),
                             " skip ", skip, " seed ", seed, " frames ", frames);
                        CHECK(stats.simdTarget == hwy::TargetName(target));
                        CHECK(test::sameBits(packets, scalar));
                        CHECK(stats.samplesPlaced == scalarStats.samplesPlaced);
                    }
                    hwy::SetSupportedTargetsForTest(0);
                }
}

TEST_CASE("pre-integration on packets equals the scalar float path bit for bit: orders, placements, jitter") {
    const Camera camera = testCamera(37, 23);
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    for (VoxelType type : {VoxelType::UInt8, VoxelType::Float32})
        for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour}) {
            const Scene scene{testVolume(type), std::nullopt, GridConvention::CellCentred,
                              testTransferFunction(emission, 9)};
            // The table and its check built once per order and step, not for every render of them.
            OccupancyCache cache;
            for (int order : {1, 2})
                for (Placement placement : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                                            Placement::EntryExitAlignCorner})
                    for (bool jitter : {false, true})
                    // A step of 0.77 voxels jumps; one of 10, longer than a stencil brick along some axis
                    // whatever the ray's direction (10 / sqrt 3 > 4), does not: once per order and placement.
                    for (double rate : !jitter && type == VoxelType::UInt8 && emission == EmissionModel::ColourTimesExtinction
                                           ? std::vector<double>{1.3, 0.1}
                                           : std::vector<double>{1.3}) {
                        RenderOptions opt;
                        opt.precision = Precision::Float;
                        opt.integrator = Integrator::Preintegrated;
                        opt.preintegrationOrder = order;
                        opt.preintegrationSize = 64;
                        opt.placement = placement;
                        opt.samplingRate = rate;
                        opt.jitter = jitter;
                        opt.simd = false;
                        // Both paths skip the table's empty space (each with its own bricks): the same bits as
                        // looking every segment up, and fewer lookups.
                        RenderStats skippingStats;
                        const Image skipping = render(scene, camera, opt, &skippingStats, &cache);
                        opt.skipEmptySpace = false;
                        RenderStats scalarStats;
                        const Image scalar = render(scene, camera, opt, &scalarStats, &cache);
                        CHECK(test::sameBits(skipping, scalar));
                        if (rate > 1) CHECK(skippingStats.samplesEvaluated < scalarStats.samplesEvaluated);
                        // Order 2's deviations are counted over the lookups that add something, the same
                        // whether empty space is skipped or not.
                        REQUIRE(scalarStats.preintegration);
                        const RenderStats::Preintegration& scalarDeltas = *scalarStats.preintegration;
                        CHECK(scalarDeltas.largestDelta.has_value() == (order == 2));
                        if (order == 2) {
                            CHECK(*scalarDeltas.largestDelta > 0.0);
                            CHECK(scalarDeltas.lookupsByDelta.size() == scalarDeltas.error.deltas.size() + 1);
                            CHECK(skippingStats.preintegration->lookupsByDelta == scalarDeltas.lookupsByDelta);
                            CHECK(skippingStats.preintegration->largestDelta == scalarDeltas.largestDelta);
                        }
                        CHECK(*std::max_element(scalar.pixels.begin(), scalar.pixels.end()) > 0.05f);
                        opt.simd = true;
                        for (std::int64_t target : targets)
                            for (bool skip : {false, true}) {
                                hwy::SetSupportedTargetsForTest(target);
                                opt.skipEmptySpace = skip;
                                RenderStats stats;
                                const Image packets = render(scene, camera, opt, &stats, &cache);
                                INFO(hwy::TargetName(target), " ", voxelTypeName(type), " order ", order, " ",
                                     placementName(placement), " jitter ", jitter, " rate ", rate, " skip ", skip);
                                CHECK(stats.simdTarget == hwy::TargetName(target));
                                CHECK(test::sameBits(packets, scalar));
                                CHECK(stats.samplesPlaced == scalarStats.samplesPlaced);
                                // At rate 0.1 only the rays the entry-exit placements give a shorter step jump.
                                if (!skip) CHECK(stats.samplesEvaluated == scalarStats.samplesEvaluated);
                                else if (rate > 1) CHECK(stats.samplesEvaluated < scalarStats.samplesEvaluated);
                                else CHECK(stats.samplesEvaluated <= scalarStats.samplesEvaluated);
                                CHECK(stats.raysHit == scalarStats.raysHit);
                                CHECK(stats.preintegration->largestDelta == scalarDeltas.largestDelta);
                                CHECK(stats.preintegration->lookupsByDelta == scalarDeltas.lookupsByDelta);
                            }
                        opt.skipEmptySpace = false;
                        hwy::SetSupportedTargetsForTest(0);
                    }
        }
}

TEST_CASE("the packet engine's rays equal pixelRay()'s: axis-aligned views, zoom, odd tiles, every target") {
    // The packets clip their rays in vectors of doubles (simd_march.cpp, RayBatch): any operation done
    // otherwise than in Camera::direction(), clipRay() or Box::toTexture() moves some ray's float entry
    // point and so the image. Looking straight down z from the volume's axis, the middle column's rays
    // have a direction of x exactly 0 (and the middle row's, y), the case left to pixelRay(); the zoom
    // and its off-centre point take the other terms of direction(); tiles of 5 and 3 pixels leave the
    // 4x4 blocks of pixels partly outside the tile.
    const Scene scene{testVolume(VoxelType::UInt8), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    std::vector<CameraSpec> views;
    const CameraSpec axis = test::cameraSpec(glm::dvec3(28.0, 10.5, -40.0), glm::dvec3(28.0, 10.5, 9.5), 50.0, 33, 25);
    views.push_back(axis);
    CameraSpec zoomed = axis;
    zoomed.eye = glm::dvec3(60.0, -20.0, 30.0);
    zoomed.zoom = 2.5;
    zoomed.zoomCentre = glm::dvec2(20.25, 9.75);
    views.push_back(zoomed);
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    for (const CameraSpec& spec : views)
        for (int tile : {16, 5, 3}) {
            const Camera camera(spec);
            RenderOptions opt;
            opt.precision = Precision::Float;
            opt.samplingRate = 3.1;
            opt.tileSize = tile;
            opt.simd = false;
            RenderStats scalarStats;
            const Image scalar = render(scene, camera, opt, &scalarStats);
            CHECK(*std::max_element(scalar.pixels.begin(), scalar.pixels.end()) > 0.05f);
            CHECK(scalarStats.raysHit > 0);
            opt.simd = true;
            for (std::int64_t target : targets) {
                hwy::SetSupportedTargetsForTest(target);
                RenderStats stats;
                const Image packets = render(scene, camera, opt, &stats);
                INFO(hwy::TargetName(target), " zoom ", spec.zoom, " tile ", tile);
                CHECK(test::sameBits(packets, scalar));
                CHECK(stats.raysHit == scalarStats.raysHit);
                CHECK(stats.samplesPlaced == scalarStats.samplesPlaced);
            }
            hwy::SetSupportedTargetsForTest(0);
        }
}

TEST_CASE("the packet engine's image does not depend on the thread count, with early termination too") {
    const Scene scene{testVolume(VoxelType::UInt8), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    const Camera camera = testCamera(53, 41);
    RenderOptions opt;
    opt.precision = Precision::Float;
    opt.samplingRate = 4.0;
    opt.tileSize = 7;
    opt.earlyTermination = 0.3;
    RenderStats one, two;
    Image a, b;
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        a = render(scene, camera, opt, &one);
    }
    {
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        b = render(scene, camera, opt, &two);
    }
    CHECK(!one.simdTarget.empty());
    CHECK(test::sameBits(a, b));
    CHECK(one.samplesPlaced == two.samplesPlaced);
    opt.simd = false;
    RenderStats scalarStats;
    CHECK(test::sameBits(render(scene, camera, opt, &scalarStats), a));
    CHECK(scalarStats.samplesPlaced == one.samplesPlaced);  // early termination stops both at the same sample
}

TEST_CASE("the packet engine's jumps across empty space skip no visible sample") {
    // 150x110x90 voxels of invisible noise holding a few visible specks of 1 to 2 voxels, far apart: a
    // lane jumps over many empty bricks at once to reach them, and a jump that went one sample too
    // far would skip a visible sample, changing the image or the count of samples evaluated.
    auto v = std::make_shared<Volume>(glm::ivec3(150, 110, 90), VoxelType::UInt8);
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> noise(0, 40);
    for (auto& voxel : v->bytes)
        voxel = static_cast<std::byte>(noise(rng));
    for (const glm::ivec3 p : {glm::ivec3(20, 30, 40), glm::ivec3(75, 55, 45), glm::ivec3(130, 90, 10),
                               glm::ivec3(100, 20, 80), glm::ivec3(60, 100, 70)})
        for (int dz = 0; dz < 2; ++dz)
            v->data<std::uint8_t>()[v->index(p.x, p.y, p.z + dz)] = static_cast<std::uint8_t>(120 + 60 * dz);
    const Scene scene{v, std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    const CameraSpec spec = test::cameraSpec(glm::dvec3(-60.0, 140.0, -120.0), glm::dvec3(75.0, 55.0, 45.0), 45.0, 61, 47);
    const Camera camera(spec);
    for (Integrator integrator : {Integrator::Riemann, Integrator::Composite})
        for (Placement placement : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                                    Placement::EntryExitAlignCorner})
            for (double rate : {1.3, 10.0}) {
                RenderOptions opt;
                opt.precision = Precision::Float;
                opt.integrator = integrator;
                opt.placement = placement;
                opt.samplingRate = rate;
                opt.simd = false;
                opt.skipEmptySpace = false;
                RenderStats marched;
                const Image all = render(scene, camera, opt, &marched);
                CHECK(*std::max_element(all.pixels.begin(), all.pixels.end()) > 0.01f);  // the specks show
                opt.simd = true;
                opt.skipEmptySpace = true;
                RenderStats skipped;
                const Image packets = render(scene, camera, opt, &skipped);
                INFO(integratorName(integrator), " ", placementName(placement), " rate ", rate);
                CHECK(test::sameBits(packets, all));
                CHECK(skipped.samplesEvaluated * 50 < marched.samplesEvaluated);  // it did skip
                // The scalar path skips by the 8^3 brick of a sample's position (with a margin), the
                // packets by the 4^3 stencil brick of its stencil: they evaluate fewer, here far fewer
                // (the specks fill a few of each). Near a brick's face the two may disagree on an
                // invisible sample the other skips, never on more.
                opt.simd = false;
                RenderStats scalar;
                render(scene, camera, opt, &scalar);
                CHECK(skipped.samplesEvaluated <= scalar.samplesEvaluated + 2);
                CHECK(skipped.samplesEvaluated * 2 < scalar.samplesEvaluated);
            }
}

TEST_CASE("the packet engine leaves invisible samples out of its sums without changing a bit") {
    // Transfer functions whose invisible stretch (where a sample adds exactly nothing) starts below the
    // first point or nowhere, ends at a point, at a jump, or covers everything, or holds only under
    // colour x extinction (colour without extinction); a dim one under --early-termination auto:0.9,
    // whose rays end after few samples; and dense ones whose steps' exponents -tau dx pass exp_kernel's
    // near-zero range (tau up to 60) and its normal range (up to 1000), so the packets take each form.
    // Each with the s below which PacketScene skips samples, under colour x extinction and under colour.
    using P = TransferFunctionPoint;
    constexpr float inf = std::numeric_limits<float>::infinity();
    struct Function {
        const char* name;
        std::vector<P> points;
        float invisibleBelow[2];
    };
    const std::vector<Function> functions{
        {"visible from the first point", {{0.0, 0.1, 0.2, 0.3, 0.4}, {1.0, 0.9, 0.5, 0.1, 0.8}}, {-inf, -inf}},
        {"invisible below 0.2", {{0.0, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}, {0.6, 0.7, 0.3, 0.2, 0.9}, {1.0, 0.1, 0.9, 0.4, 0.3}},
         {0.2f, 0.2f}},
        {"a jump at 0.3", {{0.0, 0, 0, 0, 0}, {0.3, 0, 0, 0, 0}, {0.3, 0.5, 0.5, 0.5, 0.8}, {1.0, 0.9, 0.2, 0.1, 0.4}},
         {0.3f, 0.3f}},
        {"invisible throughout", {{0.0, 0, 0, 0, 0}, {1.0, 0, 0, 0, 0}}, {inf, inf}},
        {"colour without extinction below 0.2", {{0.0, 0.9, 0.8, 0.7, 0}, {0.2, 0.9, 0.8, 0.7, 0}, {1.0, 0.5, 0.5, 0.5, 1.0}},
         {0.2f, -inf}},
        {"dim", {{0.0, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}, {1.0, 0.02, 0.01, 0.03, 0.05}}, {0.2f, 0.2f}},
        {"dense", {{0.0, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}, {0.5, 0.6, 0.3, 0.2, 20.0}, {1.0, 0.1, 0.9, 0.4, 60.0}}, {0.2f, 0.2f}},
        {"opaque", {{0.0, 0, 0, 0, 0}, {0.2, 0, 0, 0, 0}, {0.5, 0.6, 0.3, 0.2, 300.0}, {1.0, 0.1, 0.9, 0.4, 1000.0}},
         {0.2f, 0.2f}}};
    const Camera camera = testCamera(37, 23);
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    for (const auto& [name, points, invisibleBelow] : functions)
        for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour})
            for (Integrator integrator : {Integrator::Riemann, Integrator::Composite})
                for (bool skip : {true, false}) {
                    const Scene scene{testVolume(VoxelType::UInt8), std::nullopt, GridConvention::CellCentred,
                                      TransferFunction(points, emission)};
                    RenderOptions opt;
                    opt.precision = Precision::Float;
                    opt.integrator = integrator;
                    opt.samplingRate = 3.1;
                    opt.skipEmptySpace = skip;
                    const bool dim = std::string(name) == "dim";
                    if (dim) opt.terminationBound = 0.9;
                    CHECK(PacketScene(scene, camera, nullptr, opt).invisibleBelow ==
                          invisibleBelow[emission == EmissionModel::ColourTimesExtinction ? 0 : 1]);
                    opt.simd = false;
                    RenderStats scalarStats;
                    const Image scalar = render(scene, camera, opt, &scalarStats);
                    if (dim) CHECK(scalarStats.raysTerminated > 0);
                    opt.simd = true;
                    for (std::int64_t target : targets) {
                        hwy::SetSupportedTargetsForTest(target);
                        RenderStats stats;
                        const Image packets = render(scene, camera, opt, &stats);
                        INFO(name, " ", hwy::TargetName(target), " ", integratorName(integrator), " skip ", skip,
                             " emission ", static_cast<int>(emission));
                        CHECK(test::sameBits(packets, scalar));
                        CHECK(stats.samplesPlaced == scalarStats.samplesPlaced);
                        CHECK(stats.raysTerminated == scalarStats.raysTerminated);
                        if (!skip) CHECK(stats.samplesEvaluated == scalarStats.samplesEvaluated);
                    }
                    hwy::SetSupportedTargetsForTest(0);
                }
}

TEST_CASE("--simd leaves double precision, the Simpson methods and analytic fields on the scalar path") {
    const Scene scene{testVolume(VoxelType::UInt8), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    const Camera camera = testCamera(9, 7);
    RenderOptions opt;  // double
    RenderStats stats;
    render(scene, camera, opt, &stats);
    CHECK(stats.simdTarget.empty());
    opt.precision = Precision::Float;
    opt.integrator = Integrator::Simpson;
    render(scene, camera, opt, &stats);
    CHECK(stats.simdTarget.empty());
    opt.integrator = Integrator::Riemann;
    const Scene analytic{nullptr, LinearField{}, GridConvention::NodeCentred, scene.transferFunction};
    render(analytic, camera, opt, &stats);
    CHECK(stats.simdTarget.empty());
}

TEST_CASE("parseSimd takes on, off and the name of a target this CPU runs") {
    RenderOptions opt;
    parseSimd("off", "--simd", opt);
    CHECK((!opt.simd && opt.simdTarget.empty()));
    parseSimd("on", "--simd", opt);
    CHECK((opt.simd && opt.simdTarget.empty()));
    const std::vector<std::string> targets = availableSimdTargets();
    REQUIRE(!targets.empty());
    CHECK(targets.back() == hwy::TargetName(HWY_STATIC_TARGET));  // the baseline, last
    std::string lower = targets.front();
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    parseSimd(lower, "--simd", opt);
    CHECK((opt.simd && opt.simdTarget == targets.front()));
    std::string list;
    for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
    CHECK_THROWS_WITH_AS(parseSimd("yes", "--simd", opt),
                         ("--simd: unknown value 'yes' (expected on, off or a SIMD target this CPU and build have: " +
                          list + ")").c_str(),
                         Error);
}

TEST_CASE("--simd TARGET and VRI_SIMD_TARGET run the packets on that target, bit for bit as the best") {
    const Scene scene{testVolume(VoxelType::UInt16), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    const Camera camera = testCamera(23, 17);
    RenderOptions opt;
    opt.precision = Precision::Float;
    const test::ScopedEnvironment variable("VRI_SIMD_TARGET", std::nullopt);  // the process's comes back after
    RenderStats best;
    const Image reference = render(scene, camera, opt, &best);
    CHECK(best.simdTarget == availableSimdTargets().front());
    for (const std::string& target : availableSimdTargets()) {
        INFO(target);
        opt.simdTarget = target;
        RenderStats stats;
        CHECK(test::sameBits(render(scene, camera, opt, &stats), reference));
        CHECK(stats.simdTarget == target);
        opt.simdTarget.clear();
        variable.set(target);
        CHECK(test::sameBits(render(scene, camera, opt, &stats), reference));
        CHECK(stats.simdTarget == target);
        variable.set(std::nullopt);
    }
    render(scene, camera, opt, &best);  // and back to the best
    CHECK(best.simdTarget == availableSimdTargets().front());
    variable.set("AVX9000");
    CHECK_THROWS_WITH_AS(render(scene, camera, opt, &best),
                         doctest::Contains("VRI_SIMD_TARGET: 'AVX9000' is not a SIMD target this CPU and build have"),
                         Error);
}

TEST_CASE("VRI_VOXEL_LOADS: gathers and scalar loads read the same voxels, bit for bit, and none past the end") {
    // 8-bit volumes whose stencils reach their last voxel: the test volume, single layers along y and
    // along z (strides of 0, where a gathered word may pass the end), and the smallest volume. Each is
    // also marched from a copy of its bytes that ends where an inaccessible page begins: a read past the
    // last voxel (a gathered word that the end guard failed to pull back) faults, failing the run. (The
    // bricks' distances, the loads' other use, are read only with empty-space skipping: not here.)
    std::vector<std::shared_ptr<Volume>> volumes{testVolume(VoxelType::UInt8)};
    std::mt19937 rng(5);
    for (const glm::ivec3 dims : {glm::ivec3(37, 1, 19), glm::ivec3(37, 21, 1), glm::ivec3(2, 2, 1)}) {
        auto v = std::make_shared<Volume>(dims, VoxelType::UInt8);
        for (auto& voxel : v->bytes)
            voxel = static_cast<std::byte>(std::uniform_int_distribution<int>(0, 255)(rng));
        volumes.push_back(v);
    }
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    const test::ScopedEnvironment variable("VRI_VOXEL_LOADS", std::nullopt);  // the process's comes back after
    for (const auto& volume : volumes) {
        const std::size_t bytes = volume->bytes.size(), mapped = (bytes + page - 1) / page * page + page;
        struct Mapping {
            std::size_t size;
            void* at;
            ~Mapping() {
                if (at != MAP_FAILED) ::munmap(at, size);
            }
        } region{mapped, ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0)};
        REQUIRE(region.at != MAP_FAILED);
        std::byte* guard = static_cast<std::byte*>(region.at) + (mapped - page);
        REQUIRE(::mprotect(guard, page, PROT_NONE) == 0);
        std::memcpy(guard - bytes, volume->bytes.data(), bytes);

        const glm::dvec3 centre = glm::dvec3(volume->dims) / 2.0;
        const Camera camera(test::cameraSpec(centre + glm::dvec3(-30.0, 45.0, -50.0), centre, 40.0, 37, 23));
        const Scene scene{volume, std::nullopt, GridConvention::CellCentred,
                          testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
        RenderOptions opt;
        opt.precision = Precision::Float;
        opt.samplingRate = 3.3;
        opt.simd = false;
        const Image scalar = render(scene, camera, opt);
        CHECK(*std::max_element(scalar.pixels.begin(), scalar.pixels.end()) > 0.05f);
        opt.simd = true;
        for (const char* loads : {"gather", "scalar"}) {
            variable.set(loads);
            for (std::int64_t target : targets) {
                hwy::SetSupportedTargetsForTest(target);
                INFO(loads, " ", hwy::TargetName(target), " dims ", volume->dims.x, "x", volume->dims.y, "x",
                     volume->dims.z);
                RenderStats stats;
                CHECK(test::sameBits(render(scene, camera, opt, &stats), scalar));
                // The stats name the loads where they apply: on AVX2 only.
                CHECK(stats.voxelLoads == (stats.simdTarget == "AVX2" ? loads : ""));
                PacketScene packets(scene, camera, nullptr, opt);  // the same march, from the guarded copy
                CHECK(voxelLoadsName(packets.voxelLoads) == std::string(loads));
                packets.voxels = guard - bytes;
                Image image(camera.width(), camera.height());
                MarchCounts counts;
                marchPackets(packets, 0, 0, camera.width(), camera.height(), image, counts);
                CHECK(test::sameBits(image, scalar));
            }
            hwy::SetSupportedTargetsForTest(0);
        }
    }
    variable.set("vector");
    const Camera camera = testCamera(37, 23);
    RenderOptions opt;
    opt.precision = Precision::Float;
    const Scene scene{volumes.front(), std::nullopt, GridConvention::CellCentred,
                      testTransferFunction(EmissionModel::ColourTimesExtinction, 9)};
    CHECK_THROWS_WITH_AS(render(scene, camera, opt), "VRI_VOXEL_LOADS: expected gather or scalar, got 'vector'", Error);
}
