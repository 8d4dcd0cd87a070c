#pragma once
// A face of a cell whose four corners hold one scalar v, seen along a piece of a ray through the cell. The
// trilinear interpolant there factors: with a the face's axis and e its side (0 or 1), s - v = F G, where
// F = |w_a - e| >= 0 is how far, in weight, the ray is from the face, and G is the bilinear interpolant of
// the opposite face's s_k - v over the other two axes (the face's own terms vanish). So s's side of v is
// G's side of 0 wherever the ray is off the face: known as soon as the computed G is clear of 0, however
// slowly s itself leaves v. A ray leaving such a face nearly tangent to the level, where the computed s
// stays within its rounding of v over a long window, has G clear of 0 a few ulps from the face.
// exact_ray.cpp's wrong-side analysis uses it at TF points placed on such a value (TF editors for 8-bit
// data put points on data values, and constant regions of those values are common).
#include <array>

#include <glm/vec3.hpp>

#include "libvri/core/cubic.h"

namespace vri {

struct ConstantFace {
    double value;  // v: the scalar its four corners hold
    Cubic g;       // G along the piece, sigma in [0, 1] (degree 2)
    double scale;  // bounds the magnitudes whose rounding went into g, as ExactRay's sScale does for s
};

// The faces of the cell whose corners' scalars are equal, at most six, into `out`; returns their count.
// `s`: the corners' scalars as the model defines them (exact_reference.h), corner (dx, dy, dz) at index
// dx + 2 dy + 4 dz; the piece runs from cell weights w0 to w1, as trilinearAlongSegment's cubic does.
int constantFaces(const std::array<double, 8>& s, const glm::dvec3& w0, const glm::dvec3& w1, ConstantFace out[6]);

}  // namespace vri
