#pragma once
// Pinhole camera: one ray through the centre of each pixel, row 0 at the top of the image.
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "libvri/core/box.h"

namespace vri {

struct CameraSpec {
    glm::dvec3 eye{0.0, 0.0, 5.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovYDegrees = 30.0;  // full vertical field of view
    int width = 800;
    int height = 600;
    // A close-up of the same view: the image shows the frame magnified `zoom` times about
    // zoomCentre, a point of the full frame in pixels (x right, y down; unset: the frame's centre).
    // Zoom 1 about the centre gives the whole frame, bit for bit.
    double zoom = 1.0;
    std::optional<glm::dvec2> zoomCentre;
};

// Looks at the box centre along -z (+y up) from just far enough for the whole box to fit the view.
CameraSpec framingCamera(const Box& box, int width, int height, double fovYDegrees);

// The ranges a camera takes (its constructor checks them; a tool checks them first to name its option):
// a vertical field of view in (0, 180) degrees, a finite zoom >= 1.
bool validFieldOfView(double degrees);
bool validZoom(double zoom);

// What Camera::direction computes from: the orthonormal view basis, the tangents of half the fields of
// view and the zoom centre in pixels. A port of direction() (the Vulkan shaders make their rays from it)
// reproduces it from these and the spec's zoom.
struct CameraBasis {
    glm::dvec3 forward, right, up;
    double tanHalfX, tanHalfY;
    glm::dvec2 centre;
};

class Camera {
public:
    // Throws vri::Error on an image size that is not positive or too large for imageBytes(), a field of view
    // outside (0, 180), a coordinate of eye, target or up that is not finite or above 1e150 in magnitude,
    // eye and target less than 1e-150 apart, an up vector shorter than that or parallel to the view
    // direction, or a zoom that is not >= 1.
    explicit Camera(const CameraSpec& spec);

    const CameraSpec& spec() const { return spec_; }
    int width() const { return spec_.width; }
    int height() const { return spec_.height; }
    const glm::dvec3& eye() const { return spec_.eye; }
    // Unit direction of the ray through the centre of pixel (px, py).
    glm::dvec3 direction(int px, int py) const;
    CameraBasis basis() const;

private:
    CameraSpec spec_;
    glm::dvec3 forward_, right_, up_;
    double tanHalfY_, tanHalfX_;
};

}  // namespace vri
