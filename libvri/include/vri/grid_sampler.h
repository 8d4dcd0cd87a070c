#pragma once
// Trilinear reconstruction of a volume in its native voxel type, addressed in texture coordinates
// u in [0,1]^3 of the volume's box, returning the normalised scalar s of the transfer function.
#include <algorithm>
#include <cstdint>

#include <glm/vec3.hpp>

#include "vri/grid_convention.h"
#include "vri/volume.h"

namespace vri {

template <class T, class Real>
class GridSampler {
public:
    using Vec = glm::vec<3, Real>;

    GridSampler(const Volume& volume, GridConvention convention)
        : data_(volume.data<T>()), n_(volume.dims),
          stride_{1, std::int64_t(volume.dims.x), std::int64_t(volume.dims.x) * volume.dims.y} {
        const bool cell = convention == GridConvention::CellCentred;
        for (int a = 0; a < 3; ++a) {
            scale_[a] = static_cast<Real>(cell ? n_[a] : n_[a] - 1);
            offset_[a] = static_cast<Real>(cell ? 0.5 : 0.0);
            maxCoord_[a] = static_cast<Real>(n_[a] - 1);
            maxBase_[a] = std::max(n_[a] - 2, 0);
            if (n_[a] == 1) stride_[a] = 0;  // a single layer: both taps read it
        }
        const ValueRange r = volume.normalisationRange();
        lo_ = static_cast<Real>(r.lo);
        invRange_ = r.hi > r.lo ? static_cast<Real>(1.0 / (r.hi - r.lo)) : Real(0);
    }

    // Continuous voxel index of a texture coordinate: voxel i sits at index i.
    Vec index(const Vec& u) const { return u * scale_ - offset_; }

    Real operator()(const Vec& u) const {
        const Vec x = index(u);
        std::int64_t base = 0;
        Real w[3];
        for (int a = 0; a < 3; ++a) {
            // Clamp to the outermost voxels (texture "clamp to edge"); exact for node-centred data,
            // whose box ends on the outermost voxels anyway.
            const Real c = std::clamp(x[a], Real(0), maxCoord_[a]);
            const int i = std::min(static_cast<int>(c), maxBase_[a]);
            w[a] = c - static_cast<Real>(i);
            base += i * stride_[a];
        }
        const T* p = data_ + base;
        const std::int64_t sx = stride_[0], sy = stride_[1], sz = stride_[2];
        auto v = [p](std::int64_t o) { return static_cast<Real>(p[o]); };
        auto lerp = [](Real a, Real b, Real t) { return a + t * (b - a); };
        const Real c00 = lerp(v(0), v(sx), w[0]);
        const Real c10 = lerp(v(sy), v(sy + sx), w[0]);
        const Real c01 = lerp(v(sz), v(sz + sx), w[0]);
        const Real c11 = lerp(v(sz + sy), v(sz + sy + sx), w[0]);
        const Real c0 = lerp(c00, c10, w[1]);
        const Real c1 = lerp(c01, c11, w[1]);
        return (lerp(c0, c1, w[2]) - lo_) * invRange_;
    }

private:
    const T* data_;
    glm::ivec3 n_;
    std::int64_t stride_[3];
    Vec scale_{}, offset_{};
    Real maxCoord_[3];
    int maxBase_[3];
    Real lo_, invRange_;
};

}  // namespace vri
