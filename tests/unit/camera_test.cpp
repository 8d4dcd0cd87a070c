// The pinhole camera: pixel-centre rays, and close-ups that magnify a part of the same frame.
#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include "libvri/core/camera.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

CameraSpec view(int width, int height) {
    CameraSpec c;
    c.eye = {1.0, 2.0, 9.0};
    c.target = {0.5, -0.25, 0.0};
    c.width = width;
    c.height = height;
    c.fovYDegrees = 40.0;
    return c;
}

}  // namespace

TEST_CASE("camera: the middle of an odd-sized image looks at the target") {
    const Camera camera(view(101, 51));
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0.5, -0.25, 0.0) - glm::dvec3(1.0, 2.0, 9.0));
    const glm::dvec3 d = camera.direction(50, 25);
    CHECK(glm::length(d - expected) < 1e-15);
}

TEST_CASE("camera: zoom 1 about the frame centre is the whole frame, bit for bit") {
    CameraSpec zoomed = view(64, 48);
    zoomed.zoom = 1.0;
    zoomed.zoomCentre = glm::dvec2(32.0, 24.0);
    const Camera plain(view(64, 48)), same(zoomed);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) CHECK(plain.direction(x, y) == same.direction(x, y));
}

TEST_CASE("camera: a close-up shows the frame around the zoom centre, magnified") {
    CameraSpec spec = view(80, 60);
    spec.zoom = 4.0;
    spec.zoomCentre = glm::dvec2(60.0, 10.0);  // pixel corner (60, 10) of the full frame
    const Camera full(view(80, 60)), close(spec);
    // Close-up pixel (42, 32) is centred 2.5 close-up pixels = 0.625 full pixels right of and below the zoom
    // centre: at (60.625, 10.625) of the full frame, 0.125 pixel from the centre of full pixel (60, 10).
    const glm::dvec3 d = close.direction(42, 32), expected = full.direction(60, 10);
    const double pixelAngle = glm::length(full.direction(60, 10) - full.direction(61, 10));
    CHECK(glm::length(d - expected) < 0.2 * pixelAngle);
    // Four close-up pixels span one full-frame pixel.
    CHECK(glm::length(close.direction(41, 31) - close.direction(45, 31)) == doctest::Approx(pixelAngle).epsilon(1e-3));
    spec.zoom = 0.5;
    CHECK_THROWS_AS(Camera{spec}, Error);
}
