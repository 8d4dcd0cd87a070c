#include <doctest/doctest.h>

#include <limits>

#include "libvri/core/cpu_renderer.h"
#include "libvri/core/nonfinite_pixels.h"
#include "libvri/util/error.h"

using namespace vri;

TEST_CASE("non-finite pixels: counted once per pixel, the first in row order described") {
    Image image(4, 3);
    CHECK(findNonFinitePixels(image).count == 0);
    CHECK(findNonFinitePixels(image).describe() == "0 of 12 pixels are not finite");
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    image.at(3, 2, 0) = nan;
    image.at(1, 1, 2) = -inf;
    image.at(1, 1, 3) = nan;  // a second bad channel of the same pixel
    image.at(2, 1, 1) = 1.5f;  // large but finite values are fine
    image.at(0, 0, 0) = std::numeric_limits<float>::max();
    const NonFinitePixels found = findNonFinitePixels(image);
    CHECK(found.count == 2);
    CHECK(found.pixels == 12);
    CHECK(found.firstX == 1);
    CHECK(found.firstY == 1);
    CHECK(found.describe() == "2 of 12 pixels are not finite (first at 1,1: R=0 G=0 B=-inf A=nan)");
}

TEST_CASE("render: the stats count the non-finite pixels an overflowing extinction leaves") {
    // tau * dx * C = 1e300 per sample: the Riemann sum is finite in double but beyond the float image.
    const auto scene = [](double tau) {
        const TransferFunction tf({{0, 1, 1, 1, tau}, {1, 1, 1, 1, tau}}, EmissionModel::ColourTimesExtinction);
        return Scene{nullptr, LinearField{}, GridConvention::NodeCentred, tf};
    };
    CameraSpec spec;
    spec.eye = {0, 0, -6};
    spec.width = 8;
    spec.height = 8;
    const Camera camera(spec);
    RenderOptions options;
    RenderStats stats;
    render(scene(1), camera, options, &stats);
    CHECK(stats.nonfinite.count == 0);
    const Image image = render(scene(1e300), camera, options, &stats);
    CHECK(stats.nonfinite.count > 0);
    CHECK(stats.nonfinite.count == findNonFinitePixels(image).count);
    // In float the transfer function itself would overflow: refused before rendering.
    options.precision = Precision::Float;
    CHECK_THROWS_WITH_AS(render(scene(1e300), camera, options),
                         doctest::Contains("transfer function point 0 holds 1e+300"), Error);
}
