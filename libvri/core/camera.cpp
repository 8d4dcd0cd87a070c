#include "libvri/core/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "libvri/core/image.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

// The camera computes lengths as square roots of sums of squares, which overflow to infinity above
// about 1e154 and underflow to zero below about 1e-154. Within these bounds every length it takes is
// a normal double; outside them a degenerate-looking vector is only a rounding artefact, and the
// message would blame the wrong thing (an eye at 1e308 is not an up vector parallel to the view).
constexpr double kMaxCoordinate = 1e150;
constexpr double kMinLength = 1e-150;

std::string vectorText(const glm::dvec3& v) {
    return exactNumber(v.x) + "," + exactNumber(v.y) + "," + exactNumber(v.z);
}

void requireCoordinates(const glm::dvec3& v, const std::string& name) {
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(v[axis]) || std::abs(v[axis]) > kMaxCoordinate)
            throw Error("camera " + name + " " + vectorText(v) + ": coordinates must be finite and at most " +
                        exactNumber(kMaxCoordinate) + " in magnitude");
}

// |v| without the overflow or underflow of squaring its components.
double robustLength(const glm::dvec3& v) {
    const double scale = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return scale == 0.0 ? 0.0 : scale * glm::length(v / scale);
}

}  // namespace

bool validFieldOfView(double degrees) { return degrees > 0.0 && degrees < 180.0; }

bool validZoom(double zoom) { return zoom >= 1.0 && std::isfinite(zoom); }

CameraSpec framingCamera(const Box& box, int width, int height, double fovYDegrees) {
    CameraSpec c;
    c.width = width;
    c.height = height;
    c.fovYDegrees = fovYDegrees;
    c.target = box.centre();
    const double aspect = height > 0 ? static_cast<double>(width) / height : 1.0;
    const double halfY = 0.5 * fovYDegrees * std::numbers::pi / 180.0;
    const double halfMin = std::min(halfY, std::atan(std::tan(halfY) * aspect));
    const double radius = 0.5 * robustLength(box.size());
    c.eye = c.target + glm::dvec3(0.0, 0.0, radius / std::sin(halfMin));
    return c;
}

Camera::Camera(const CameraSpec& spec) : spec_(spec) {
    imageBytes(spec.width, spec.height);  // before anything sizes a buffer per pixel (rays, bounds)
    if (!validZoom(spec.zoom))
        throw Error("zoom must be a finite factor >= 1, got " + std::to_string(spec.zoom));
    // A close-up magnifies a part of the frame: a centre outside it (or not finite) would show what the frame
    // does not, and a huge one would move the rays' directions beyond what a pixel resolves.
    if (spec.zoomCentre) {
        const glm::dvec2 c = *spec.zoomCentre;
        if (!(c.x >= 0.0 && c.x <= spec.width && c.y >= 0.0 && c.y <= spec.height))
            throw Error("zoom centre " + exactNumber(c.x) + "," + exactNumber(c.y) + " is outside the frame [0, " +
                        std::to_string(spec.width) + "] x [0, " + std::to_string(spec.height) + "] pixels");
    }
    if (!validFieldOfView(spec.fovYDegrees))
        throw Error("field of view must be in (0, 180) degrees, got " + std::to_string(spec.fovYDegrees));
    requireCoordinates(spec.eye, "eye");
    requireCoordinates(spec.target, "target");
    requireCoordinates(spec.up, "up vector");
    const glm::dvec3 view = spec.target - spec.eye;
    const double distance = robustLength(view);
    if (distance == 0.0) throw Error("camera eye and target coincide at " + vectorText(spec.eye));
    if (distance < kMinLength)
        throw Error("camera eye and target are only " + exactNumber(distance) + " apart, below the " +
                    exactNumber(kMinLength) + " the camera resolves (is the scene, e.g. its voxel spacing, that small?)");
    const double upLength = robustLength(spec.up);
    if (upLength < kMinLength)
        throw Error("camera up vector " + vectorText(spec.up) + " is zero or shorter than " + exactNumber(kMinLength));
    forward_ = view / distance;
    const glm::dvec3 side = glm::cross(forward_, spec.up / upLength);
    if (glm::length(side) < 1e-12) throw Error("camera up vector is parallel to the view direction");
    right_ = glm::normalize(side);
    up_ = glm::cross(right_, forward_);
    tanHalfY_ = std::tan(0.5 * spec.fovYDegrees * std::numbers::pi / 180.0);
    tanHalfX_ = tanHalfY_ * static_cast<double>(spec.width) / spec.height;
}

CameraBasis Camera::basis() const {
    return {forward_, right_, up_, tanHalfX_, tanHalfY_,
            spec_.zoomCentre.value_or(glm::dvec2(0.5 * spec_.width, 0.5 * spec_.height))};
}

glm::dvec3 Camera::direction(int px, int py) const {
    // The pixel's centre in the full frame; with zoom 1 about the centre this is exactly px + 0.5.
    const glm::dvec2 centre = basis().centre;
    const double fx = centre.x + (px + 0.5 - 0.5 * spec_.width) / spec_.zoom;
    const double fy = centre.y + (py + 0.5 - 0.5 * spec_.height) / spec_.zoom;
    const double x = (2.0 * fx / spec_.width - 1.0) * tanHalfX_;
    const double y = (1.0 - 2.0 * fy / spec_.height) * tanHalfY_;
    return glm::normalize(forward_ + x * right_ + y * up_);
}

}  // namespace vri
