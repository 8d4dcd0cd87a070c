#pragma once
// Scalar fields given by a formula, rendered exactly (no grid) or sampled onto a grid.
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "libvri/core/box.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/volume.h"

namespace vri {

// Paper A's test field: f = (x + 1.5) / 3 on the 3-unit cube centred at the origin, i.e. a ramp from
// 0 to 1 along x across the box. `dims` is the grid the field stands for; the sample placements of
// paper A need it (`length(ray * dim)`), and sampleOntoGrid() uses it.
struct LinearField {
    Box box{glm::dvec3(-1.5), glm::dvec3(1.5)};
    glm::ivec3 dims{5, 5, 5};

    double operator()(const glm::dvec3& p) const { return (p.x - box.lo.x) / (box.hi.x - box.lo.x); }
};

// Sampler with the interface of GridSampler: texture coordinate in, normalised scalar out.
template <class Real>
struct LinearFieldSampler {
    Real operator()(const glm::vec<3, Real>& u) const { return u.x; }
};

// The field at the grid's sample points as a float32 volume with range [0, 1], placed so that its
// box under `convention` is the field's box.
Volume sampleOntoGrid(const LinearField& field, GridConvention convention);

// Box of a volume's samples under a convention: cell-centred volumes span dims * spacing,
// node-centred ones (dims - 1) * spacing, both starting at volume.origin.
Box volumeBox(const Volume& volume, GridConvention convention);
Box gridBox(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 origin, GridConvention convention);

}  // namespace vri
