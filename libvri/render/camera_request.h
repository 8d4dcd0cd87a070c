#pragma once
// A camera as the tools' --size, --eye, --target, --up, --fov, --zoom and --zoom-centre (and Python's
// vri.Camera) ask for it: the eye and the target where the framing puts them (framingCamera) unless given.
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "libvri/core/box.h"
#include "libvri/core/camera.h"

namespace vri {

struct CameraRequest {
    glm::ivec2 size{800, 600};
    std::optional<glm::dvec3> eye, target;
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov = 30.0, zoom = 1.0;
    std::optional<glm::dvec2> zoomCentre;

    // The camera looking at `box`: framed to see all of it, then what was given put in place.
    CameraSpec spec(const Box& box) const {
        CameraSpec spec = framingCamera(box, size.x, size.y, fov);
        if (target) spec.target = *target;
        if (eye) spec.eye = *eye;
        spec.up = up;
        spec.zoom = zoom;
        spec.zoomCentre = zoomCentre;
        return spec;
    }
};

}  // namespace vri
