#include "libvri/core/analytic_field.h"

#include <glm/common.hpp>

namespace vri {

Box volumeBox(const Volume& volume, GridConvention convention) {
    return gridBox(volume.dims, volume.spacing, volume.origin, convention);
}

Box gridBox(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 origin, GridConvention convention) {
    const glm::dvec3 n(dims);
    const glm::dvec3 cells = convention == GridConvention::CellCentred ? n : n - glm::dvec3(1.0);
    return {origin, origin + cells * spacing};
}

Volume sampleOntoGrid(const LinearField& field, GridConvention convention) {
    Volume v(field.dims, VoxelType::Float32);
    const bool cell = convention == GridConvention::CellCentred;
    const glm::dvec3 n(field.dims);
    v.spacing = field.box.size() / (cell ? n : glm::max(n - glm::dvec3(1.0), glm::dvec3(1.0)));
    v.origin = field.box.lo;
    v.range = ValueRange{0.0, 1.0};
    float* out = v.data<float>();
    const double offset = cell ? 0.5 : 0.0;
    for (int z = 0; z < v.dims.z; ++z)
        for (int y = 0; y < v.dims.y; ++y)
            for (int x = 0; x < v.dims.x; ++x) {
                const glm::dvec3 p = v.origin + (glm::dvec3(x, y, z) + offset) * v.spacing;
                out[v.index(x, y, z)] = static_cast<float>(field(p));
            }
    return v;
}

}  // namespace vri
