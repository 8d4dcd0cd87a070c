// The accurate reference against closed forms (paper A's linear field, a cubic along a cell's
// diagonal, transfer-function jumps and breakpoints inside a cell), the Riemann sum converging to it,
// its error bound and its independence of the thread count.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <hwy/targets.h>
#include <tbb/global_control.h>

#include "test_camera.h"
#include "libvri/core/cubic.h"
#include "libvri/core/exact_gauss_batch.h"
#include "libvri/core/exact_ray.h"
#include "libvri/core/exact_empty_space.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/util/error.h"

using namespace vri;
using V = glm::dvec3;

namespace {

TransferFunction paperATransferFunction() {  // g(s) = s, tau(s) = s / 2
    return TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, 0.5}}, EmissionModel::Colour);
}

double maxBound(const ExactReference& ref) {
    double m = 0.0;
    for (double b : ref.bounds) m = std::max(m, b);
    return m;
}

// Paper A's closed form for every pixel: F = length (f(entry) + f(exit)) / 2, I = 2 (1 - exp(-F / 2)).
void checkLinearFieldClosedForm(const Scene& scene) {
    const CameraSpec spec = test::cameraSpec(V(-4.0, 1.5, 2.5), V(0.1, -0.2, 0.0), 40.0, 24, 18);
    const Camera camera(spec);
    const ExactReference ref = renderExactReference(scene, camera);
    const LinearField field;
    int hit = 0;
    for (int py = 0; py < spec.height; ++py)
        for (int px = 0; px < spec.width; ++px) {
            const V dir = camera.direction(px, py);
            const auto seg = clipRay(camera.eye(), dir, field.box);
            double colour = 0.0, alpha = 0.0;
            if (seg && seg->tFar > seg->tNear) {
                ++hit;
                const double length = seg->tFar - seg->tNear;
                const double F = length *
                                 (field(camera.eye() + seg->tNear * dir) + field(camera.eye() + seg->tFar * dir)) / 2;
                colour = 2.0 * (1.0 - std::exp(-F / 2));
                alpha = 1.0 - std::exp(-F / 2);
            }
            const double* v = &ref.values[(static_cast<std::size_t>(py) * spec.width + px) * 4];
            for (int c = 0; c < 3; ++c) CHECK(std::abs(v[c] - colour) < 1e-9);
            CHECK(std::abs(v[3] - alpha) < 1e-9);
        }
    CHECK(hit > spec.width * spec.height / 4);
    CHECK(maxBound(ref) < 1e-9);
}

// A 2x2x2 node-centred volume whose only non-zero voxel is (1, 1, 1) = 1: the field in the unit cube is
// x y z, so along the diagonal from (0, 0, 0) to (1, 1, 1) it is s = lambda^3 over a length of sqrt 3.
Scene cornerCell(TransferFunction tf) {
    auto v = std::make_shared<Volume>(glm::ivec3(2), VoxelType::Float32);
    v->data<float>()[7] = 1.0f;
    v->range = ValueRange{0.0, 1.0};
    return Scene{v, std::nullopt, GridConvention::NodeCentred, std::move(tf)};
}

// The one pixel of a ray along that diagonal.
ExactReference diagonalRay(const Scene& scene) {
    CameraSpec spec;
    spec.eye = V(-1.0);
    spec.target = V(0.5);
    spec.width = spec.height = 1;
    return renderExactReference(scene, Camera(spec));
}

std::shared_ptr<Volume> noisyBlob(glm::ivec3 dims, VoxelType type, glm::dvec3 spacing) {
    auto v = std::make_shared<Volume>(dims, type);
    v->spacing = spacing;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(0.0, 0.3);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const V p = (V(x, y, z) + 0.5) / V(dims) - 0.5;
                const double value = std::clamp(1.0 - 2.0 * std::sqrt(glm::dot(p, p)) + noise(rng), 0.0, 1.0);
                const std::size_t i = v->index(x, y, z);
                if (type == VoxelType::UInt8) v->data<std::uint8_t>()[i] = static_cast<std::uint8_t>(value * 255);
                if (type == VoxelType::UInt16) v->data<std::uint16_t>()[i] = static_cast<std::uint16_t>(value * 65535);
                if (type == VoxelType::Float32) v->data<float>()[i] = static_cast<float>(value);
            }
    return v;
}

TransferFunction blobTransferFunction() {  // invisible low values, a jump, colours changing with s
    return TransferFunction({{0.0, 0, 0, 0, 0},
                             {0.3, 0, 0, 0, 0},
                             {0.5, 0.9, 0.4, 0.1, 0.4},
                             {0.5, 0.2, 0.8, 0.3, 1.2},
                             {1.0, 1, 1, 1, 0.6}},
                            EmissionModel::ColourTimesExtinction);
}

Camera blobCamera(const Scene& scene) {
    CameraSpec spec = framingCamera(scene.box(), 20, 16, 30.0);
    spec.eye = scene.box().centre() + V(7.0, 4.0, 9.0);
    return Camera(spec);
}

}  // namespace

TEST_CASE("cubic: the trilinear interpolant along a segment is the product of the weights") {
    std::array<double, 8> corner{};
    corner[7] = 1.0;
    const Cubic diagonal = trilinearAlongSegment(corner, V(0.0), V(1.0));
    CHECK(diagonal.c == std::array<double, 4>{0.0, 0.0, 0.0, 1.0});

    // Any corners and any segment: the cubic equals trilinear interpolation at every point.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 20; ++trial) {
        for (double& c : corner) c = u(rng) * 100.0;
        const V w0(u(rng), u(rng), u(rng)), w1(u(rng), u(rng), u(rng));
        const Cubic p = trilinearAlongSegment(corner, w0, w1);
        for (double sigma : {0.0, 0.3, 0.71, 1.0}) {
            const V w = w0 + sigma * (w1 - w0);
            double expected = 0.0;
            for (int k = 0; k < 8; ++k)
                expected += corner[k] * ((k & 1) ? w.x : 1 - w.x) * ((k & 2) ? w.y : 1 - w.y) * ((k & 4) ? w.z : 1 - w.z);
            CHECK(p(sigma) == doctest::Approx(expected).epsilon(1e-13));
        }
    }
}

TEST_CASE("cubic: critical points, monotone roots to full precision and reparameterisation") {
    const Cubic p{{0.0, 0.56, -1.5, 1.0}};  // p' = 3 x^2 - 3 x + 0.56
    double critical[2];
    REQUIRE(criticalPoints(p, 0.0, 1.0, critical) == 2);
    CHECK(critical[0] == doctest::Approx((3.0 - std::sqrt(2.28)) / 6.0).epsilon(1e-15));
    CHECK(critical[1] == doctest::Approx((3.0 + std::sqrt(2.28)) / 6.0).epsilon(1e-15));
    CHECK(criticalPoints(p, 0.3, 0.7, critical) == 0);

    const Cubic cube{{0.0, 0.0, 0.0, 1.0}};
    const double root = solveMonotone(cube, 0.5, 0.0, 1.0);
    CHECK(std::abs(root - std::cbrt(0.5)) <= 2e-16);
    const Cubic falling{{1.0, -1.0, 0.0, 0.0}};
    CHECK(solveMonotone(falling, 0.25, 0.0, 1.0) == 0.75);
    // Started on the chord, roots as good: a residual within rounding of the midpoint start's (near a
    // flat end x is only known to rounding / slope), rising and falling, steep and flat.
    for (const Cubic& q : {cube, falling, Cubic{{0.1, 0.9, -0.2, 0.15}}, Cubic{{0.9, -0.05, -1.5, 0.7}}}) {
        const double q0 = q(0.0), q1 = q(1.0);
        for (double f : {1e-9, 0.01, 0.3, 0.5, 0.77, 0.999999}) {
            const double level = q0 + f * (q1 - q0);
            const double mid = solveMonotone(q, level, 0.0, 1.0, RootStart::Midpoint);
            const double chord = solveMonotone(q, level, 0.0, 1.0, RootStart::Chord);
            CAPTURE(level);
            CHECK(std::abs(chord - mid) <= 1e-14);
            CHECK(std::abs(q(chord) - level) <= std::abs(q(mid) - level) + 4.0 * std::numeric_limits<double>::epsilon());
        }
    }

    const Cubic shifted = p.reparameterised(0.2, 0.5);
    for (double y : {0.0, 0.4, 1.0}) CHECK(shifted(y) == doctest::Approx(p(0.2 + 0.5 * y)).epsilon(1e-14));
}

TEST_CASE("exact reference matches paper A's closed form on the linear field") {
    checkLinearFieldClosedForm(Scene{nullptr, LinearField{}, GridConvention::NodeCentred, paperATransferFunction()});
    auto grid = std::make_shared<Volume>(sampleOntoGrid(LinearField{}, GridConvention::NodeCentred));
    checkLinearFieldClosedForm(Scene{grid, std::nullopt, GridConvention::NodeCentred, paperATransferFunction()});
}

TEST_CASE("exact reference integrates the cubic along a cell's diagonal") {
    // Emission = colour, C = s, tau = k s with s = lambda^3, dt = sqrt 3 dlambda:
    // depth D = sqrt 3 k / 4, I = (1 - exp(-D)) / k, alpha = 1 - exp(-D).
    const double k = 2.0;
    const Scene scene = cornerCell(TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, k}}, EmissionModel::Colour));
    const ExactReference ref = diagonalRay(scene);
    const double alpha = 1.0 - std::exp(-std::sqrt(3.0) * k / 4);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(ref.values[c] - alpha / k) < 1e-13);
    CHECK(std::abs(ref.values[3] - alpha) < 1e-13);
    CHECK(maxBound(ref) < 1e-12);
}

TEST_CASE("exact reference splits at transfer-function breakpoints and jumps inside a cell") {
    // Red while s < 0.5, blue after: tau = s up to s = 0.25, then 3 s - 0.5 up to 0.5, where it
    // jumps from 1 to 2, then 2 s + 1. With g = C tau and C constant per part, I = C (T_a - T_b).
    const TransferFunction tf({{0.0, 1, 0, 0, 0.0},
                               {0.25, 1, 0, 0, 0.25},
                               {0.5, 1, 0, 0, 1.0},
                               {0.5, 0, 0, 1, 2.0},
                               {1.0, 0, 0, 1, 3.0}},
                              EmissionModel::ColourTimesExtinction);
    const double r3 = std::sqrt(3.0);
    const double l1 = std::cbrt(0.25), l2 = std::cbrt(0.5);
    const double d1 = r3 * std::pow(l1, 4) / 4;
    const double d2 = d1 + r3 * (3 * (std::pow(l2, 4) - std::pow(l1, 4)) / 4 - 0.5 * (l2 - l1));
    const double d3 = d2 + r3 * ((1 - std::pow(l2, 4)) / 2 + (1 - l2));
    const ExactReference ref = diagonalRay(cornerCell(tf));
    CHECK(std::abs(ref.values[0] - (1 - std::exp(-d2))) < 1e-13);
    CHECK(ref.values[1] == 0.0);
    CHECK(std::abs(ref.values[2] - (std::exp(-d2) - std::exp(-d3))) < 1e-13);
    CHECK(std::abs(ref.values[3] - (1 - std::exp(-d3))) < 1e-13);
    CHECK(maxBound(ref) < 1e-12);
    CHECK(ref.stats.subPieces == 3);  // s crosses 0.25 and 0.5 (the jump) once each
}

TEST_CASE("Riemann sums converge to the exact reference, whose bound is tiny") {
    for (auto [type, convention] : {std::pair{VoxelType::UInt8, GridConvention::CellCentred},
                                    std::pair{VoxelType::UInt16, GridConvention::NodeCentred},
                                    std::pair{VoxelType::Float32, GridConvention::CellCentred}}) {
        CAPTURE(voxelTypeName(type));
        const Scene scene{noisyBlob(glm::ivec3(9, 8, 7), type, V(1.0, 0.75, 1.0)), std::nullopt, convention,
                          blobTransferFunction()};
        const Camera camera = blobCamera(scene);
        const ExactReference ref = renderExactReference(scene, camera);
        CHECK(maxBound(ref) < 1e-9);
        CHECK(ref.stats.raysHit > 0);
        double previous = 0.0;
        for (double step : {0.1, 0.01, 0.001}) {
            RenderOptions opt;
            opt.samplingRate = 1.0 / step;
            const Image riemann = render(scene, camera, opt);
            double error = 0.0;
            for (std::size_t i = 0; i < riemann.pixels.size(); ++i)
                error = std::max(error, std::abs(riemann.pixels[i] - ref.values[i]));
            CAPTURE(step);
            CHECK(error < 20 * step);
            if (previous > 0.0) CHECK(error < previous / 4);  // first order, ~10x per step
            previous = error;
        }
    }
}

TEST_CASE("exact reference does not depend on the thread count") {
    const Scene scene{noisyBlob(glm::ivec3(10), VoxelType::UInt8, V(1.0)), std::nullopt, GridConvention::CellCentred,
                      blobTransferFunction()};
    const Camera camera = blobCamera(scene);
    ExactReferenceOptions opt;
    opt.tileSize = 4;
    ExactReference one, many;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = renderExactReference(scene, camera, opt);
    }
    many = renderExactReference(scene, camera, opt);
    CHECK(one.values == many.values);
    CHECK(one.bounds == many.bounds);
    CHECK(one.stats.subPieces == many.stats.subPieces);
}

namespace {

// |a - b| <= a's bound + b's bound + the rounding of the comparison, pixel by pixel and channel by channel.
void checkWithinBounds(const ExactReference& a, const ExactReference& b) {
    REQUIRE(a.values.size() == b.values.size());
    int outside = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i)
        if (std::abs(a.values[i] - b.values[i]) > a.bounds[i] + b.bounds[i] + 1e-16 * std::abs(b.values[i])) ++outside;
    CHECK(outside == 0);
}

Scene largeBlob(TransferFunction tf) {  // 40^3: its corners are empty bricks of the occupancy grid
    return Scene{noisyBlob(glm::ivec3(40), VoxelType::UInt8, V(1.0)), std::nullopt, GridConvention::CellCentred,
                 std::move(tf)};
}

// The blob's transfer function with every extinction multiplied by `k`.
TransferFunction scaledBlobTransferFunction(double k) {
    std::vector<TransferFunctionPoint> points = blobTransferFunction().points();
    for (TransferFunctionPoint& p : points) p.tau *= k;
    return TransferFunction(points, EmissionModel::ColourTimesExtinction);
}

struct PiecesWalked {
    std::uint64_t skipping, all;
};

// Renders with and without skipping empty space: the same values, bounds and visible pieces (some).
PiecesWalked checkSkippingChangesNoBit(const Scene& scene, const Camera& camera) {
    ExactReferenceOptions walkAll;
    walkAll.skipEmptySpace = false;
    const ExactReference skipping = renderExactReference(scene, camera);
    const ExactReference all = renderExactReference(scene, camera, walkAll);
    CHECK(skipping.values == all.values);
    CHECK(skipping.bounds == all.bounds);
    CHECK(skipping.stats.piecesVisible == all.stats.piecesVisible);
    CHECK(skipping.stats.subPieces == all.stats.subPieces);
    CHECK(skipping.stats.piecesVisible > 0);
    return {skipping.stats.pieces, all.stats.pieces};
}

}  // namespace

TEST_CASE("exact reference: jumping over empty bricks changes no bit and walks fewer pieces") {
    for (GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred}) {
        Scene scene = largeBlob(blobTransferFunction());
        scene.convention = convention;
        CameraSpec spec = framingCamera(scene.box(), 48, 40, 35.0);
        for (const V& offset : {V(70.0, 45.0, 90.0), V(-3.0, 2.0, 95.0), V(0.5, -80.0, 0.25)}) {
            spec.eye = scene.box().centre() + offset;
            const PiecesWalked pieces = checkSkippingChangesNoBit(scene, Camera(spec));
            CHECK(pieces.skipping < pieces.all);
        }
    }
}

namespace {

// A 150x70x90 volume, empty but for two small noisy blobs far apart: most of its 32^3-cell regions
// are empty, so the walk jumps whole regions, and some rays pass both blobs.
Scene sparseScene(GridConvention convention) {
    const glm::ivec3 dims(150, 70, 90);
    auto v = std::make_shared<Volume>(dims, VoxelType::UInt8);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> noise(0.0, 0.3);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                double value = 0.0;
                for (const V& centre : {V(30.0, 35.0, 40.0), V(118.0, 30.0, 55.0)}) {
                    const double r = glm::length(V(x, y, z) - centre) / 12.0;
                    if (r < 1.0) value = std::max(value, std::clamp(1.0 - r + noise(rng), 0.0, 1.0));
                }
                v->data<std::uint8_t>()[v->index(x, y, z)] = static_cast<std::uint8_t>(value * 255);
            }
    return Scene{v, std::nullopt, convention, blobTransferFunction()};
}

}  // namespace

TEST_CASE("exact reference: the empty space's regions are empty exactly where all their blocks are") {
    const Scene scene = sparseScene(GridConvention::CellCentred);
    const ExactEmptySpace empty(*scene.volume, scene.transferFunction);
    const glm::ivec3 blocks = empty.blocks();
    CHECK(blocks == glm::ivec3(38, 18, 23));  // cells 0..148, 0..68, 0..88 in blocks of 4
    int emptyRegions = 0, regions = 0;
    for (int rz = 0; rz * 8 < blocks.z; ++rz)
        for (int ry = 0; ry * 8 < blocks.y; ++ry)
            for (int rx = 0; rx * 8 < blocks.x; ++rx) {
                bool all = true;
                for (int z = rz * 8; z < std::min(rz * 8 + 8, blocks.z); ++z)
                    for (int y = ry * 8; y < std::min(ry * 8 + 8, blocks.y); ++y)
                        for (int x = rx * 8; x < std::min(rx * 8 + 8, blocks.x); ++x) {
                            const int m[3] = {x, y, z};
                            all = all && empty.emptyBlock(m);
                        }
                const int m[3] = {rx * 8, ry * 8, rz * 8};
                CHECK(empty.emptyRegionOf(m) == all);
                emptyRegions += all;
                ++regions;
            }
    CHECK(emptyRegions > regions / 2);
    CHECK(emptyRegions < regions);
}

TEST_CASE("exact reference: jumping over empty regions changes no bit") {
    for (GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred}) {
        const Scene scene = sparseScene(convention);
        CameraSpec spec = framingCamera(scene.box(), 40, 30, 40.0);
        // Along the long axis through both blobs, across it, and from a corner.
        for (const V& offset : {V(-190.0, 3.0, 8.0), V(4.0, -6.0, 160.0), V(150.0, 120.0, -130.0)}) {
            spec.eye = scene.box().centre() + offset;
            const PiecesWalked pieces = checkSkippingChangesNoBit(scene, Camera(spec));
            CHECK(pieces.skipping * 4 < pieces.all);
        }
    }
}

TEST_CASE("exact reference: a cache hands the empty space to the next frame of the same volume and TF only") {
    const Scene scene = sparseScene(GridConvention::CellCentred);
    CameraSpec spec = framingCamera(scene.box(), 24, 18, 40.0);
    spec.eye = scene.box().centre() + V(-190.0, 3.0, 8.0);
    const Camera camera(spec);
    ExactReferenceOptions options;
    options.tolerance = 1e-7;
    OccupancyCache cache;
    const ExactReference alone = renderExactReference(scene, camera, options);
    CHECK_FALSE(alone.stats.setupReused);
    const ExactReference first = renderExactReference(scene, camera, options, &cache);
    const ExactReference second = renderExactReference(scene, camera, options, &cache);
    CHECK_FALSE(first.stats.setupReused);
    CHECK(second.stats.setupReused);
    CHECK(second.stats.setupSeconds == first.stats.setupSeconds);
    CHECK(first.values == alone.values);
    CHECK(second.values == alone.values);
    CHECK(second.bounds == alone.bounds);
    // Another transfer function (visible from lower values on) gets its own empty space.
    std::vector<TransferFunctionPoint> points = scene.transferFunction.points();
    points[1].s = 0.1;
    const Scene wider{scene.volume, std::nullopt, scene.convention,
                      TransferFunction(points, EmissionModel::ColourTimesExtinction)};
    const ExactReference changed = renderExactReference(wider, camera, options, &cache);
    CHECK_FALSE(changed.stats.setupReused);
    CHECK(changed.values == renderExactReference(wider, camera, options).values);
    CHECK(changed.values != alone.values);
}

TEST_CASE("exact reference: rays end early within the stated bound") {
    const Scene scene = largeBlob(scaledBlobTransferFunction(20.0));
    const Camera camera = blobCamera(scene);
    ExactReferenceOptions tight, loose;
    tight.tolerance = 1e-14;
    loose.tolerance = 1e-6;
    const ExactReference a = renderExactReference(scene, camera, tight);
    const ExactReference b = renderExactReference(scene, camera, loose);
    CHECK(b.stats.raysOpaque > b.stats.raysHit / 10);
    CHECK(b.stats.piecesVisible < a.stats.piecesVisible);
    checkWithinBounds(a, b);
    CHECK(maxBound(a) < 1e-12);
}

TEST_CASE("exact reference: a looser tolerance costs less and stays within its bound") {
    const Scene scene = largeBlob(scaledBlobTransferFunction(4.0));
    const Camera camera = blobCamera(scene);
    ExactReferenceOptions opt;
    opt.tolerance = 1e-13;
    const ExactReference reference = renderExactReference(scene, camera, opt);
    std::uint64_t previousNodes = reference.stats.quadratureNodes;
    for (double tolerance : {1e-11, 1e-9, 1e-7, 1e-5, 1e-3}) {
        CAPTURE(tolerance);
        opt.tolerance = tolerance;
        const ExactReference r = renderExactReference(scene, camera, opt);
        checkWithinBounds(reference, r);
        CHECK(maxBound(r) <= 100.0 * tolerance);
        CHECK(r.stats.quadratureNodes <= previousNodes);
        previousNodes = r.stats.quadratureNodes;
    }
    CHECK(previousNodes < reference.stats.quadratureNodes / 3);
    // A tolerance far below rounding ends (each sub-piece has an interval budget) within its bound.
    opt.tolerance = 1e-300;
    const ExactReference tiny = renderExactReference(scene, camera, opt);
    checkWithinBounds(reference, tiny);
    CHECK(tiny.stats.quadratureIntervals <= 4096 * tiny.stats.subPieces);
}

TEST_CASE("exact reference: the batched Gauss rules give the same bits on every Highway target and thread count") {
    // From 1e-10 up the Gauss rules run in batches of sub-pieces, one per vector lane
    // (exact_gauss_batch.h). A thin medium sends rays through more sub-pieces than a batch holds; a thick
    // one needs many panels or the adaptive quadrature; both emission models.
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    for (double scale : {0.05, 4.0, 300.0})
        for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour}) {
            std::vector<TransferFunctionPoint> points = scaledBlobTransferFunction(scale).points();
            const Scene scene = largeBlob(TransferFunction(points, emission));
            const Camera camera = blobCamera(scene);
            ExactReferenceOptions opt;
            opt.tolerance = 1e-13;
            const ExactReference reference = renderExactReference(scene, camera, opt);
            opt.tolerance = 1e-7;
            ExactReference first;
            {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
                first = renderExactReference(scene, camera, opt);
            }
            CAPTURE(scale);
            CAPTURE(static_cast<int>(emission));
            checkWithinBounds(reference, first);
            // Thin: 48 sub-pieces per ray on average, the rays through the middle well over a batch.
            if (scale == 0.05) CHECK(2 * first.stats.subPieces > GaussBatch::kCapacity * first.stats.raysHit);
            if (scale == 300.0) CHECK(first.stats.quadratureIntervals > first.stats.subPieces);
            for (std::int64_t target : targets) {
                hwy::SetSupportedTargetsForTest(target);
                INFO(hwy::TargetName(target));
                const ExactReference r = renderExactReference(scene, camera, opt);
                CHECK(std::string(gaussBatchTarget()) == hwy::TargetName(target));
                CHECK(r.values == first.values);
                CHECK(r.bounds == first.bounds);
                CHECK(r.stats.quadratureNodes == first.stats.quadratureNodes);
            }
            hwy::SetSupportedTargetsForTest(0);
        }
}

TEST_CASE("exact reference: the bound holds for every extinction from 1e-6 to 1e300") {
    const CameraSpec spec = test::cameraSpec(V(-4.0, 1.5, 2.5), V(0.1, -0.2, 0.0), 40.0, 12, 9);
    const Camera camera(spec);
    // A constant field of s = 1 (a cell-centred 2^3 volume filling the linear field's box) under a
    // constant TF, g = C tau: colour C (1 - exp(-tau L)). The linear field s = u.x under C = s,
    // tau = k s, g = C: with F = k L (s_entry + s_exit) / 2, colour (1 - exp(-F)) / k.
    auto constant = std::make_shared<Volume>(glm::ivec3(2), VoxelType::Float32);
    for (int i = 0; i < 8; ++i) constant->data<float>()[i] = 1.0f;
    constant->range = ValueRange{0.0, 1.0};
    constant->spacing = V(1.5);
    constant->origin = V(-1.5);
    const LinearField field;
    for (int e = -6; e <= 300; e += 6) {
        const double k = std::pow(10.0, e);
        CAPTURE(k);
        const double C[3] = {0.9, 0.5, 0.25};
        const Scene uniform{constant, std::nullopt, GridConvention::CellCentred,
                            TransferFunction({{0, C[0], C[1], C[2], k}, {1, C[0], C[1], C[2], k}},
                                             EmissionModel::ColourTimesExtinction)};
        const Scene linear{nullptr, field, GridConvention::NodeCentred,
                           TransferFunction({{0, 0, 0, 0, 0}, {1, 1, 1, 1, k}}, EmissionModel::Colour)};
        const ExactReference a = renderExactReference(uniform, camera), b = renderExactReference(linear, camera);
        REQUIRE(uniform.box().lo == field.box.lo);
        REQUIRE(uniform.box().hi == field.box.hi);
        int outside = 0, hit = 0;
        double worst = 0.0;
        for (int py = 0; py < spec.height; ++py)
            for (int px = 0; px < spec.width; ++px) {
                const V dir = camera.direction(px, py);
                const auto seg = clipRay(camera.eye(), dir, field.box);
                if (!seg || !(seg->tFar > seg->tNear)) continue;
                ++hit;
                const double L = seg->tFar - seg->tNear;
                const double opacity = -std::expm1(-k * L);
                const double F = k * L * (field(camera.eye() + seg->tNear * dir) + field(camera.eye() + seg->tFar * dir)) / 2;
                const double linearAlpha = -std::expm1(-F);
                const std::size_t at = (static_cast<std::size_t>(py) * spec.width + px) * 4;
                // The closed forms in double carry a few roundings of their own (and of L, F).
                auto check = [&](const ExactReference& r, int c, double truth) {
                    const double error = std::abs(r.values[at + c] - truth);
                    worst = std::max(worst, r.bounds[at + c]);
                    if (error > r.bounds[at + c] + 1e-14 * std::abs(truth)) ++outside;
                };
                for (int c = 0; c < 3; ++c) {
                    check(a, c, C[c] * opacity);
                    check(b, c, linearAlpha / k);
                }
                check(a, 3, opacity);
                check(b, 3, linearAlpha);
            }
        CHECK(hit > 0);
        CHECK(outside == 0);
        // The bound stays useful up to 1e4 per unit length; beyond, the allowance for a split misplaced by
        // rounding (4 u length max g) grows with tau until [0, C_max] caps it.
        if (k <= 1e4) CHECK(worst < 1e-9);
    }
    const Scene overflowing{constant, std::nullopt, GridConvention::CellCentred,
                            TransferFunction({{0, 1, 1, 1, 1e307}, {1, 1, 1, 1, 1e307}},
                                             EmissionModel::ColourTimesExtinction)};
    CHECK_THROWS_AS(renderExactReference(overflowing, camera), Error);
}

TEST_CASE("exact reference: 8-bit voxels (a visibility table) give the bits of the same values as float") {
    const Scene bytes = largeBlob(blobTransferFunction());
    auto floats = std::make_shared<Volume>(bytes.volume->dims, VoxelType::Float32);
    for (std::size_t i = 0; i < floats->voxelCount(); ++i)
        floats->data<float>()[i] = static_cast<float>(bytes.volume->data<std::uint8_t>()[i]);
    floats->range = ValueRange{0.0, 255.0};
    const Scene asFloat{floats, std::nullopt, GridConvention::CellCentred, blobTransferFunction()};
    const Camera camera = blobCamera(bytes);
    const ExactReference a = renderExactReference(bytes, camera), b = renderExactReference(asFloat, camera);
    CHECK(a.values == b.values);
    CHECK(a.bounds == b.bounds);
    CHECK(a.stats.piecesVisible == b.stats.piecesVisible);
}

TEST_CASE("exact ray: the table of zero spans answers as TransferFunction::isInvisible, jumps included") {
    const std::vector<TransferFunction> tfs = {
        TransferFunction({{0.0, 0, 0, 0, 0}, {0.15, 0, 0, 0, 0}, {0.3, 0.2, 0.6, 0.1, 0.15}, {1.0, 1, 1, 1, 1}},
                         EmissionModel::ColourTimesExtinction),
        // A jump out of zero at 0.5 and into zero at 0.7, a zero point inside, zero colour with extinction.
        TransferFunction({{0.2, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}, {0.5, 1, 0, 0, 2}, {0.7, 1, 0, 0, 2}, {0.7, 0, 0, 0, 0},
                          {0.8, 0, 0, 0, 0}, {0.9, 0, 0, 0, 1}, {0.95, 1, 0, 0, 0}},
                         EmissionModel::ColourTimesExtinction),
        // g = C: colour alone makes a point visible.
        TransferFunction({{0.0, 0, 0, 0, 0}, {0.4, 0, 0, 0, 0}, {0.6, 0.5, 0, 0, 0}, {0.8, 0, 0, 0, 0}},
                         EmissionModel::Colour)};
    std::vector<double> s = {-1.0, 1.5};
    for (const TransferFunction& tf : tfs)
        for (const auto& p : tf.points())
            for (double d : {-1e-3, 0.0, 1e-3}) {
                s.push_back(p.s + d);
                s.push_back(std::nextafter(p.s + d, -1.0));
                s.push_back(std::nextafter(p.s + d, 2.0));
            }
    std::sort(s.begin(), s.end());
    for (const TransferFunction& tf : tfs) {
        const ExactRay ray(tf, 1e-7);
        int agree = 0;
        for (std::size_t i = 0; i < s.size(); ++i)
            for (std::size_t j = i; j < s.size(); ++j) {
                CAPTURE(s[i]);
                CAPTURE(s[j]);
                CHECK(ray.invisible(s[i], s[j]) == tf.isInvisible(s[i], s[j]));
                agree += ray.invisible(s[i], s[j]);
            }
        CHECK(agree > 0);
    }
}

TEST_CASE("exact reference: a transfer function of many points (binary searches for its segments) stays within bounds") {
    // The same function twice: 21 points (their segments found by counting), and 301 points that put 14
    // more on each of its segments, collinear (found by binary search, past 64 points). The two images
    // differ only by the roundings of different splits: within the sum of their bounds.
    const auto at = [](double s) {
        const int i = std::min(19, static_cast<int>(s * 20));  // segment i of the 21 points' 20
        const double k = (s * 20 - i);
        const auto tau = [](int j) { return j < 4 ? 0.0 : 0.05 * (1 + j % 5); };
        const auto red = [](int j) { return 0.5 + 0.4 * std::sin(0.35 * j); };
        return TransferFunctionPoint{s, red(i) + k * (red(i + 1) - red(i)), 0.3, 0.2,
                                     tau(i) + k * (tau(i + 1) - tau(i))};
    };
    std::vector<TransferFunctionPoint> few, many;
    for (int i = 0; i <= 20; ++i) few.push_back(at(i / 20.0));
    for (int i = 0; i <= 300; ++i) many.push_back(at(i / 300.0));
    many.back() = few.back();  // s = 1 exactly
    const Scene coarse = largeBlob(TransferFunction(few, EmissionModel::ColourTimesExtinction));
    const Scene fine = largeBlob(TransferFunction(many, EmissionModel::ColourTimesExtinction));
    const Camera camera = blobCamera(coarse);
    for (double tolerance : {1e-13, 1e-7}) {
        CAPTURE(tolerance);
        ExactReferenceOptions opt;
        opt.tolerance = tolerance;
        const ExactReference a = renderExactReference(coarse, camera, opt), b = renderExactReference(fine, camera, opt);
        checkWithinBounds(a, b);
        CHECK(b.stats.subPieces > 5 * a.stats.subPieces);  // it did split at many more levels
        CHECK(*std::max_element(a.values.begin(), a.values.end()) > 0.1);
    }
}
