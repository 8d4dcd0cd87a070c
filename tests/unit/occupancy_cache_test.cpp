// OccupancyCache: a render reuses the empty-space grid of an earlier frame only when the volume object,
// the convention and the transfer function (points and emission) are the ones it was built for, and an
// image rendered with the cache is bit for bit the image rendered without it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "same_bits.h"
#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/occupancy_cache.h"

using namespace vri;

namespace {

// A 29x23x17 volume: s rises from 0 at a corner to 1 at the far one, so that a transfer function's
// zero range decides which bricks are empty.
std::shared_ptr<Volume> rampVolume() {
    auto v = std::make_shared<Volume>(glm::ivec3(29, 23, 17), VoxelType::UInt8);
    for (int z = 0; z < 17; ++z)
        for (int y = 0; y < 23; ++y)
            for (int x = 0; x < 29; ++x)
                v->data<std::uint8_t>()[v->index(x, y, z)] =
                    static_cast<std::uint8_t>(std::lround(255.0 * (x / 28.0 + y / 22.0 + z / 16.0) / 3.0));
    return v;
}

// Zero below `from`, visible above; the colour is non-zero everywhere, so that under emission
// `Colour` no brick is empty.
TransferFunction rampTransferFunction(double from, EmissionModel emission = EmissionModel::ColourTimesExtinction) {
    return TransferFunction({{0.0, 0.5, 0.4, 0.3, 0.0}, {from, 0.5, 0.4, 0.3, 0.0}, {1.0, 0.9, 0.2, 0.1, 0.8}},
                            emission);
}

Scene rampScene(std::shared_ptr<const Volume> volume, TransferFunction tf) {
    Scene scene{std::move(volume), std::nullopt, GridConvention::CellCentred, std::move(tf)};
    return scene;
}

Camera rampCamera() {
    const CameraSpec spec = test::cameraSpec(glm::dvec3(-20.0, 35.0, -40.0), glm::dvec3(14.5, 11.5, 8.5), 40.0, 37, 23);
    return Camera(spec);
}

}  // namespace

TEST_CASE("the occupancy cache hands back its grid only for the volume and transfer function it was built for") {
    const auto volume = rampVolume();
    const TransferFunction half = rampTransferFunction(0.5), third = rampTransferFunction(0.3);
    OccupancyCache cache;
    const auto first = cache.grid(volume, GridConvention::CellCentred, half);
    CHECK_FALSE(first.reused);
    const double built = first.buildSeconds;
    const auto again = cache.grid(volume, GridConvention::CellCentred, rampTransferFunction(0.5));
    CHECK(again.reused);
    CHECK(again.buildSeconds == built);
    CHECK(&again.structure == &first.structure);

    // A changed transfer function, emission model, convention or volume object gets a new grid, equal
    // to one built from scratch.
    const auto check = [&](const std::shared_ptr<const Volume>& v, GridConvention convention,
                           const TransferFunction& tf) {
        const auto e = cache.grid(v, convention, tf);
        CHECK_FALSE(e.reused);
        CHECK(e.structure.emptyFlags() == OccupancyGrid(*v, convention, tf).emptyFlags());
    };
    check(volume, GridConvention::CellCentred, third);
    CHECK(cache.grid(volume, GridConvention::CellCentred, third).structure.emptyFraction() <
          OccupancyGrid(*volume, GridConvention::CellCentred, half).emptyFraction());
    check(volume, GridConvention::CellCentred, rampTransferFunction(0.3, EmissionModel::Colour));
    CHECK(cache.grid(volume, GridConvention::CellCentred, rampTransferFunction(0.3, EmissionModel::Colour))
              .structure.emptyFraction() == 0.0);
    check(volume, GridConvention::NodeCentred, rampTransferFunction(0.3, EmissionModel::Colour));
    check(rampVolume(), GridConvention::NodeCentred, rampTransferFunction(0.3, EmissionModel::Colour));
}

TEST_CASE("the occupancy cache keeps the packet engine's stencil bricks beside the grid, under the same key") {
    const auto volume = rampVolume();
    const TransferFunction half = rampTransferFunction(0.5);
    OccupancyCache cache;
    CHECK_FALSE(cache.grid(volume, GridConvention::CellCentred, half).reused);
    const auto first = cache.stencilBricks(volume, GridConvention::CellCentred, half, 0b0001);
    CHECK_FALSE(first.reused);  // a grid of the same key does not make the stencil bricks
    CHECK(first.structure.octants() == 0b0001);
    const auto again = cache.stencilBricks(volume, GridConvention::CellCentred, half, 0b0001);
    CHECK(again.reused);
    CHECK(&again.structure == &first.structure);
    // Another octant is built on the same bricks, and only it: this call's time is the octant's.
    const auto more = cache.stencilBricks(volume, GridConvention::CellCentred, half, 0b1000'0001);
    CHECK_FALSE(more.reused);
    CHECK(&more.structure == &first.structure);
    CHECK(more.structure.octants() == 0b1000'0001);
    CHECK(cache.stencilBricks(volume, GridConvention::CellCentred, half, 0b1000'0000).reused);
    CHECK(cache.grid(volume, GridConvention::CellCentred, half).reused);  // neither drops the other
    const TransferFunction third = rampTransferFunction(0.3);
    const auto changed = cache.stencilBricks(volume, GridConvention::CellCentred, third, 0xFF);
    CHECK_FALSE(changed.reused);
    StencilBricks fresh(*volume, GridConvention::CellCentred, third), old(*volume, GridConvention::CellCentred, half);
    fresh.addOctants(0xFF);
    old.addOctants(0xFF);
    CHECK(changed.structure.distances() == fresh.distances());
    CHECK(changed.structure.distances() != old.distances());
    CHECK_FALSE(cache.grid(volume, GridConvention::CellCentred, third).reused);  // the new key dropped the grid
}

TEST_CASE("a render with the occupancy cache equals one without, and a changed transfer function gets a new grid") {
    const auto volume = rampVolume();
    const Camera camera = rampCamera();
    for (const Precision precision : {Precision::Double, Precision::Float})
        for (const bool simd : {true, false}) {
            CAPTURE(precisionName(precision));
            CAPTURE(simd);
            RenderOptions options;
            options.precision = precision;
            options.simd = simd;
            options.samplingRate = 3.0;
            OccupancyCache cache;
            const auto frame = [&](const TransferFunction& tf, bool reused) {
                const Scene scene = rampScene(volume, tf);
                RenderStats cached, alone;
                const Image image = render(scene, camera, options, &cached, &cache);
                CHECK(cached.setupReused == reused);
                CHECK(test::sameBits(image, render(scene, camera, options, &alone)));
                CHECK_FALSE(alone.setupReused);
                CHECK(cached.emptyBrickFraction == alone.emptyBrickFraction);
                CHECK(cached.samplesEvaluated == alone.samplesEvaluated);
                return image;
            };
            const Image a = frame(rampTransferFunction(0.5), false);
            CHECK(test::sameBits(a, frame(rampTransferFunction(0.5), true)));
            // Rendered with the first transfer function's grid, the second would skip bricks it can see.
            const Image b = frame(rampTransferFunction(0.3), false);
            CHECK_FALSE(test::sameBits(a, b));
            CHECK(test::sameBits(a, frame(rampTransferFunction(0.5), false)));
        }
}
