// The exact method's per-pixel bound against the truth, on the inputs where a bound is hardest to keep:
// transfer functions with thin pulses (1e-12 to 1e-4 wide in s), jumps and huge extinctions, crossed by
// rays along which the scalar barely changes (grazing the analytic field's planes of equal s, near-tangent
// to a trilinear field's iso-surfaces). Every pixel and channel of vri's result, at every tolerance from
// 1e-13 (the scalar adaptive quadrature, vri-reference) to 1e-3 (the batched Gauss rules of vri-render
// --method exact), must lie within its bound of the integral along the same ray in quadruple precision
// (quad_precision_ray.h).
//
// The arbiter's quadruple precision is software arithmetic (libquadmath): the full suites take minutes.
// `make test` runs the quick tier, a third of each suite's transfer functions (every third, so that each
// width, extinction, shape and emission model keeps cases); `make test-full` (VRI_TEST_TIER=full) runs all.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "quad_precision_ray.h"
#include "test_camera.h"
#include "libvri/core/analytic_field.h"
#include "libvri/core/camera.h"
#include "libvri/core/exact_reference.h"

using namespace vri;
using V = glm::dvec3;

namespace {

constexpr double kTolerances[] = {1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3};

// The quick tier's transfer functions: every third (all of them in the full tier).
std::vector<std::pair<std::string, TransferFunction>> tierOf(std::vector<std::pair<std::string, TransferFunction>> tfs) {
    const char* tier = std::getenv("VRI_TEST_TIER");
    if (tier && std::string(tier) == "full") return tfs;
    std::vector<std::pair<std::string, TransferFunction>> quick;
    for (std::size_t i = 0; i < tfs.size(); i += 3) quick.push_back(std::move(tfs[i]));
    MESSAGE("quick tier: " << quick.size() << " of " << tfs.size() << " transfer functions (make test-full runs all)");
    return quick;
}

struct Excess {
    int outside = 0;        // pixel-channels whose true error exceeds the bound
    double worstRatio = 0;  // the largest true error / bound
    std::string worst;      // where it is
    // Per tolerance of kTolerances, over all pixel-channels: the largest true error and the largest bound.
    std::vector<double> maxError, maxBound;
};

// The truth along every pixel's ray (of `region`, where given), then vri at every tolerance against it.
Excess checkBounds(const Scene& scene, const Camera& camera, const std::string& what,
                   std::optional<PixelRegion> region = std::nullopt) {
    const PixelRegion pixels = region.value_or(PixelRegion::whole(camera.width(), camera.height()));
    test::QuadPrecisionRay arbiter(scene.transferFunction);
    std::vector<test::Quad> truth;
    for (int py = pixels.y; py < pixels.y + pixels.height; ++py)
        for (int px = pixels.x; px < pixels.x + pixels.width; ++px) {
            const auto v = arbiter.pixel(scene, camera, px, py);
            truth.insert(truth.end(), v.begin(), v.end());
        }
    Excess excess;
    for (double tolerance : kTolerances) {
        ExactReferenceOptions options;
        options.tolerance = tolerance;
        options.region = region;
        const ExactReference r = renderExactReference(scene, camera, options);
        excess.maxError.push_back(0.0);
        excess.maxBound.push_back(0.0);
        for (std::size_t i = 0; i < truth.size(); ++i) {
            const double error = static_cast<double>(fabsq(test::Quad(r.values[i]) - truth[i]));
            excess.maxError.back() = std::max(excess.maxError.back(), error);
            excess.maxBound.back() = std::max(excess.maxBound.back(), r.bounds[i]);
            if (error > r.bounds[i]) {
                ++excess.outside;
                if (excess.outside <= 3)
                    MESSAGE(what << " tolerance " << tolerance << " pixel " << pixels.x + i / 4 % pixels.width << ","
                                 << pixels.y + i / 4 / pixels.width << " channel " << i % 4 << ": error " << error
                                 << " bound " << r.bounds[i]);
            }
            if (error / r.bounds[i] > excess.worstRatio) {
                excess.worstRatio = error / r.bounds[i];
                excess.worst = "tolerance " + std::to_string(tolerance) + " channel " + std::to_string(i % 4) + ": " +
                               std::to_string(r.values[i]) + " against " + std::to_string(static_cast<double>(truth[i])) +
                               ", bound " + std::to_string(r.bounds[i]);
            }
        }
    }
    if (excess.worstRatio > 0.1)
        MESSAGE(what << ": worst true error / bound " << excess.worstRatio << " (" << excess.worst << "), " << excess.outside
                     << " outside");
    return excess;
}

// A transfer function zero but for a pulse of extinction and colour `width` wide at s = centre: a tent
// (continuous, slope tau / (width / 2)) or a box (two jumps).
TransferFunction pulse(double centre, double width, double tau, bool box, EmissionModel emission) {
    const double lo = centre - width / 2, hi = centre + width / 2;
    if (box)
        return TransferFunction({{0, 0, 0, 0, 0}, {lo, 0, 0, 0, 0}, {lo, 0.9, 0.5, 0.2, tau}, {hi, 0.3, 0.6, 1.0, tau},
                                 {hi, 0, 0, 0, 0}, {1, 0, 0, 0, 0}},
                                emission);
    return TransferFunction({{0, 0, 0, 0, 0}, {lo, 0, 0, 0, 0}, {centre, 0.9, 0.5, 0.2, tau}, {hi, 0, 0, 0, 0},
                             {1, 0, 0, 0, 0}},
                            emission);
}

// A jump of extinction and colour at s = at, from a faint medium to a dense one.
TransferFunction jump(double at, double tau, EmissionModel emission) {
    return TransferFunction({{0, 0.2, 0.2, 0.2, 1e-3}, {at, 0.2, 0.2, 0.2, 1e-3}, {at, 1.0, 0.4, 0.7, tau}, {1, 0.5, 1.0, 0.1, tau}},
                            emission);
}

// Cameras on the analytic field s = (x + 1.5) / 3 whose rays barely move in x: each looks along -z from
// x = 8 k at x = 0 (s = 1/2) in the box's centre plane, over a field of view that spreads the rays' slope
// in x by about +-15 % around k, so that they all cross s = 1/2 inside the box; one looks straight down
// the plane x = 0 (its middle column lies in it: s = 1/2 all along); the last across the planes.
std::vector<Camera> grazingCameras() {
    std::vector<Camera> cameras;
    for (double k : {1e-3, 1e-6, 1e-9, 1e-12})
        cameras.emplace_back(test::cameraSpec(V(8.0 * k, 0.2, 8.0), V(0.0, 0.1, 0.0),
                                              2.0 * std::atan(0.12 * k) * 180.0 / M_PI, 10, 8));
    cameras.emplace_back(test::cameraSpec(V(0.0, 0.2, 8.0), V(0.0, 0.1, 0.0), 1e-4, 9, 8));
    cameras.emplace_back(test::cameraSpec(V(-4.0, 1.5, 2.5), V(0.1, -0.2, 0.0), 40.0, 10, 8));
    return cameras;
}

}  // namespace

TEST_CASE("exact bound, adversarial: thin pulses and jumps on the analytic field, grazing rays, huge tau") {
    const LinearField field;
    std::vector<std::pair<std::string, TransferFunction>> tfs;
    for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour}) {
        const std::string model = emission == EmissionModel::Colour ? " g=C" : " g=C tau";
        for (double width : {1e-12, 1e-9, 1e-6, 1e-4}) {
            // tau such that a ray at slope k = 1e-6 (s changing by ~3e-7 per unit) gathers a depth of
            // order one across the pulse, and a thousand times that.
            for (double tau : {1e-6 / width, 1e-3 / width})
                for (bool box : {false, true})
                    tfs.emplace_back((box ? "box " : "tent ") + std::to_string(width) + " tau " + std::to_string(tau) + model,
                                     pulse(0.5, width, tau, box, emission));
        }
        for (double tau : {1.0, 1e3, 1e9}) tfs.emplace_back("jump tau " + std::to_string(tau) + model, jump(0.5, tau, emission));
    }
    int outside = 0;
    const std::vector<Camera> cameras = grazingCameras();
    for (const auto& [name, tf] : tierOf(tfs))
        for (std::size_t c = 0; c < cameras.size(); ++c) {
            const Scene scene{nullptr, field, GridConvention::NodeCentred, tf};
            outside += checkBounds(scene, cameras[c], name + " camera " + std::to_string(c)).outside;
        }
    CHECK(outside == 0);
}

namespace {

// A 12^3 uint8 volume: a noisy ball whose values step by whole raw values, so that whole cells sit
// exactly on a TF point (s constant on the level) and rays graze the iso-surfaces of every value.
std::shared_ptr<Volume> steppedBall() {
    auto v = std::make_shared<Volume>(glm::ivec3(12), VoxelType::UInt8);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> noise(0, 2);
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) {
                const double r = glm::length(V(x, y, z) - V(5.5)) / 6.0;
                const int value = std::clamp(static_cast<int>(200.0 * (1.0 - r)) / 20 * 20 + noise(rng) * (x % 3 == 0), 0, 255);
                v->data<std::uint8_t>()[v->index(x, y, z)] = static_cast<std::uint8_t>(value);
            }
    return v;
}

}  // namespace

TEST_CASE("exact bound, adversarial: thin pulses and jumps in trilinear fields, near-tangent and grazing rays") {
    std::vector<std::pair<std::string, TransferFunction>> tfs;
    for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour}) {
        const std::string model = emission == EmissionModel::Colour ? " g=C" : " g=C tau";
        // Centred on a raw value (the plateaus) and between two.
        for (double centre : {100.0 / 255.0, 0.5})
            for (double width : {1e-12, 1e-9, 1e-6, 1e-4})
                for (bool box : {false, true})
                    tfs.emplace_back((box ? "box " : "tent ") + std::to_string(width) + " at " + std::to_string(centre) + model,
                                     pulse(centre, width, 1e-4 / width, box, emission));
        tfs.emplace_back("jump tau 1e4" + model, jump(100.0 / 255.0, 1e4, emission));
    }
    int outside = 0;
    // The ball from outside and from inside, one camera along a row of voxel centres (rays in the planes
    // of the grid), one nearly so.
    const Scene ball{steppedBall(), std::nullopt, GridConvention::CellCentred, tfs.front().second};
    const V centre = ball.box().centre();
    std::vector<Camera> cameras = {
        Camera(test::cameraSpec(centre + V(17.0, 9.0, 25.0), centre, 30.0, 10, 8)),
        Camera(test::cameraSpec(V(5.5, 6.5, 40.0), V(5.5, 6.5, 0.0), 3.0, 10, 8)),
        Camera(test::cameraSpec(V(5.5 + 1e-9, 6.5, 40.0), V(5.5, 6.5 - 1e-9, 0.0), 1e-6, 10, 8))};
    // The analytic field's ramp sampled onto a node-centred 5^3 grid (trilinear: the same ramp), under
    // the analytic field's grazing cameras.
    const auto ramp = std::make_shared<Volume>(sampleOntoGrid(LinearField{}, GridConvention::NodeCentred));
    for (const auto& [name, tf] : tierOf(tfs)) {
        for (std::size_t c = 0; c < cameras.size(); ++c)
            outside += checkBounds(Scene{ball.volume, std::nullopt, GridConvention::CellCentred, tf}, cameras[c],
                                   "ball, " + name + " camera " + std::to_string(c)).outside;
        if (tf.points()[2].s > 0.45) {  // the ramp's pulses at s = 1/2, where the cameras graze
            const std::vector<Camera> grazing = grazingCameras();
            for (std::size_t c = 0; c < grazing.size(); ++c)
                outside += checkBounds(Scene{ramp, std::nullopt, GridConvention::NodeCentred, tf}, grazing[c],
                                       "ramp, " + name + " camera " + std::to_string(c)).outside;
        }
    }
    CHECK(outside == 0);
}

namespace {

// The TF's steepest slope in s over all channels, between points at different s.
double steepestSlope(const TransferFunction& tf) {
    const auto& p = tf.points();
    double steepest = 0.0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i)
        if (p[i + 1].s > p[i].s)
            for (const auto& [a, b] :
                 {std::pair{p[i].r, p[i + 1].r}, {p[i].g, p[i + 1].g}, {p[i].b, p[i + 1].b}, {p[i].tau, p[i + 1].tau}})
                steepest = std::max(steepest, std::abs(b - a) / (p[i + 1].s - p[i].s));
    return steepest;
}

// A 12^3 uint8 volume of constant 3^3 blocks, each holding one of a few raw values: many cells whose eight
// corners hold one value, whose scalar sits exactly where a TF editor for 8-bit data puts its points.
std::shared_ptr<Volume> constantBlocks(const std::vector<int>& values) {
    auto v = std::make_shared<Volume>(glm::ivec3(12), VoxelType::UInt8);
    std::mt19937 rng(11);
    std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
    std::vector<int> block(64);
    for (int& b : block) b = values[pick(rng)];
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x)
                v->data<std::uint8_t>()[v->index(x, y, z)] =
                    static_cast<std::uint8_t>(block[(x / 3) + 4 * (y / 3) + 16 * (z / 3)]);
    return v;
}

}  // namespace

TEST_CASE("exact bound, adversarial: TF points at the values of 8-bit data on constant cells stay cheap") {
    // Points at raw value k, spelled as a TF file would give it (k / 255, which may differ from the voxels'
    // k * (1 / 255) by an ulp) and as the voxels' own scalar: a pulse 1e-9 wide starting there, and a jump.
    const double r = 1.0 / 255.0;
    std::vector<std::pair<std::string, TransferFunction>> tfs;
    for (EmissionModel emission : {EmissionModel::ColourTimesExtinction, EmissionModel::Colour}) {
        const std::string model = emission == EmissionModel::Colour ? " g=C" : " g=C tau";
        for (const auto& [spelling, at] :
             {std::pair{"1/255", 1.0 / 255.0}, {"1 r", 1.0 * r}, {"3/255", 3.0 / 255.0}, {"3 r", 3.0 * r},
              {"33/255", 33.0 / 255.0}, {"33 r", 33.0 * r}}) {  // 33 r is an ulp below 33/255: the cells below the point
            tfs.emplace_back(std::string("pulse from ") + spelling + model,
                             TransferFunction({{0, 0, 0, 0, 0},
                                               {at, 0, 0, 0, 0},
                                               {at, 0.9, 0.5, 0.2, 0.3},
                                               {at + 1e-9, 0.3, 0.6, 1.0, 0.3},
                                               {at + 1e-9, 0, 0, 0, 0},
                                               {1, 0, 0, 0, 0}},
                                              emission));
            tfs.emplace_back(std::string("jump at ") + spelling + model, jump(at, 0.5, emission));
        }
    }
    const auto volume = constantBlocks({0, 1, 3, 33, 100});
    const Scene blocks{volume, std::nullopt, GridConvention::CellCentred, tfs.front().second};
    const V centre = blocks.box().centre();
    const std::vector<Camera> cameras = {
        Camera(test::cameraSpec(centre + V(17.0, 9.0, 25.0), centre, 30.0, 10, 8)),
        Camera(test::cameraSpec(V(4.5, 4.5, 40.0), V(4.5, 4.5, 0.0), 3.0, 9, 7))};  // the middle ray in two voxel planes
    int outside = 0;
    for (const auto& [name, tf] : tfs)
        for (std::size_t c = 0; c < cameras.size(); ++c) {
            const Scene scene{volume, std::nullopt, GridConvention::CellCentred, tf};
            const std::string what = name + " camera " + std::to_string(c);
            const Excess excess = checkBounds(scene, cameras[c], what);
            outside += excess.outside;
            // Useful as well as sound: at every tolerance the largest bound is within 100 times the largest of
            // the true error, ten times the tolerance asked (a pixel's bound sums it over the ray's sub-pieces, and
            // a rule's rigorous bound may sit far above an error it beat by luck) and what s's rounding (some
            // 1e-16) may do through the TF's steepest slope (the pulse's 6e8 per unit s: 1e-7 where a ray lingers
            // in it). A TF point on a constant cell made it about 1 at every tolerance.
            const double roundingFloor = 1e-14 * (1.0 + steepestSlope(tf));
            for (std::size_t t = 0; t < std::size(kTolerances); ++t) {
                INFO(what << " tolerance " << kTolerances[t] << ": max bound " << excess.maxBound[t] << ", max true error "
                          << excess.maxError[t]);
                CHECK(excess.maxBound[t] <= 100.0 * std::max({excess.maxError[t], 10.0 * kTolerances[t], roundingFloor}));
            }
        }
    CHECK(outside == 0);
}

// render_exact.sh's scene (tests/tools): 3^3 blocks of raw 0, 1, 3 and 100 (Python's random.seed(11) there,
// written out here), a pulse 1e-9 wide from 1/255 and a jump at 3/255, seen down z as `vri-render --size
// 400x300 --fov 20` sees it. Near the image's top right corner rays leave a face of a block of 3 tangent to
// the level, s - 3/255 = -k (1 - sigma)^2 along a whole voxel: the computed s stays within its rounding of
// the level over the piece, and the largest bound was 0.82 (of a true error of 1e-16) before the constant
// faces' analysis (constant_face.h) told s's side from the face's opposite corners.
TEST_CASE("exact bound, adversarial: rays leaving a face that holds a TF point, tangent to the level") {
    const int blocks[64] = {100, 100, 100, 1, 1, 100, 1,   0,   100, 3,   1, 0,   0, 100, 100, 1,
                            0,   0,   0,   0, 1, 1,   0,   100, 3,   100, 1, 1,   3, 100, 0,   0,
                            100, 3,   100, 0, 3, 3,   1,   3,   0,   0,   0, 100, 0, 3,   100, 0,
                            0,   0,   1,   1, 0, 100, 100, 100, 100, 0,   1, 3,   3, 0,   3,   3};
    auto volume = std::make_shared<Volume>(glm::ivec3(12), VoxelType::UInt8);
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x)
                volume->data<std::uint8_t>()[volume->index(x, y, z)] =
                    static_cast<std::uint8_t>(blocks[x / 3 + 4 * (y / 3) + 16 * (z / 3)]);
    const double one = 1.0 / 255.0, three = 3.0 / 255.0;
    const TransferFunction tf({{0, 0, 0, 0, 0},
                               {one, 0, 0, 0, 0},
                               {one, 0.9, 0.5, 0.2, 0.3},
                               {one + 1e-9, 0.3, 0.6, 1.0, 0.3},
                               {one + 1e-9, 0, 0, 0, 0},
                               {three, 0, 0, 0, 0},
                               {three, 1.0, 0.4, 0.7, 0.5},
                               {1, 0.5, 1.0, 0.1, 0.5}},
                              EmissionModel::ColourTimesExtinction);
    const Scene scene{volume, std::nullopt, GridConvention::CellCentred, tf};
    const Camera camera(test::cameraSpec(V(4.5, 4.5, 40.0), V(4.5, 4.5, 0.0), 20.0, 400, 300));
    const Excess excess = checkBounds(scene, camera, "tangent at a face", PixelRegion{336, 0, 16, 14});
    CHECK(excess.outside == 0);
    for (std::size_t t = 0; t < std::size(kTolerances); ++t) {
        INFO("tolerance " << kTolerances[t] << ": max bound " << excess.maxBound[t] << ", max true error "
                          << excess.maxError[t]);
        CHECK(excess.maxBound[t] <= 100.0 * std::max(excess.maxError[t], 10.0 * kTolerances[t]) + 1e-8);
    }
}
