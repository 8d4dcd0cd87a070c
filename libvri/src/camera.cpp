#include "vri/camera.h"

#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "vri/error.h"

namespace vri {

CameraSpec framingCamera(const Box& box, int width, int height, double fovYDegrees) {
    CameraSpec c;
    c.width = width;
    c.height = height;
    c.fovYDegrees = fovYDegrees;
    c.target = box.centre();
    const double aspect = height > 0 ? static_cast<double>(width) / height : 1.0;
    const double halfY = 0.5 * fovYDegrees * std::numbers::pi / 180.0;
    const double halfMin = std::min(halfY, std::atan(std::tan(halfY) * aspect));
    const double radius = 0.5 * glm::length(box.size());
    c.eye = c.target + glm::dvec3(0.0, 0.0, radius / std::sin(halfMin));
    return c;
}

Camera::Camera(const CameraSpec& spec) : spec_(spec) {
    if (spec.width <= 0 || spec.height <= 0)
        throw Error("image size must be positive, got " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height));
    if (!(spec.zoom >= 1.0) || !std::isfinite(spec.zoom))
        throw Error("zoom must be a finite factor >= 1, got " + std::to_string(spec.zoom));
    if (!(spec.fovYDegrees > 0.0 && spec.fovYDegrees < 180.0))
        throw Error("field of view must be in (0, 180) degrees, got " + std::to_string(spec.fovYDegrees));
    const glm::dvec3 view = spec.target - spec.eye;
    if (glm::length(view) == 0.0) throw Error("camera eye and target coincide");
    forward_ = glm::normalize(view);
    const glm::dvec3 side = glm::cross(forward_, spec.up);
    if (glm::length(side) < 1e-12) throw Error("camera up vector is parallel to the view direction");
    right_ = glm::normalize(side);
    up_ = glm::cross(right_, forward_);
    tanHalfY_ = std::tan(0.5 * spec.fovYDegrees * std::numbers::pi / 180.0);
    tanHalfX_ = tanHalfY_ * static_cast<double>(spec.width) / spec.height;
}

glm::dvec3 Camera::direction(int px, int py) const {
    // The pixel's centre in the full frame; with zoom 1 about the centre this is exactly px + 0.5.
    const glm::dvec2 centre = spec_.zoomCentre.value_or(glm::dvec2(0.5 * spec_.width, 0.5 * spec_.height));
    const double fx = centre.x + (px + 0.5 - 0.5 * spec_.width) / spec_.zoom;
    const double fy = centre.y + (py + 0.5 - 0.5 * spec_.height) / spec_.zoom;
    const double x = (2.0 * fx / spec_.width - 1.0) * tanHalfX_;
    const double y = (1.0 - 2.0 * fy / spec_.height) * tanHalfY_;
    return glm::normalize(forward_ + x * right_ + y * up_);
}

}  // namespace vri
