#pragma once
// A unit test's camera in one call: eye, target, vertical field of view and image size (up +y, no zoom).
#include <glm/vec3.hpp>

#include "libvri/core/camera.h"

namespace vri::test {

inline CameraSpec cameraSpec(const glm::dvec3& eye, const glm::dvec3& target, double fovYDegrees, int width,
                             int height) {
    CameraSpec spec;
    spec.eye = eye;
    spec.target = target;
    spec.fovYDegrees = fovYDegrees;
    spec.width = width;
    spec.height = height;
    return spec;
}

}  // namespace vri::test
