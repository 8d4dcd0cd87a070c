#pragma once
// Trilinear reconstruction of a volume in its native voxel type, addressed in texture coordinates
// u in [0,1]^3 of the volume's box, returning the normalised scalar s of the transfer function.
#include <algorithm>
#include <cstdint>

#include <glm/vec3.hpp>

#include "libvri/core/grid_convention.h"
#include "libvri/core/volume.h"

namespace vri {

// How texture coordinates u in [0,1]^3 address a grid of `dims` voxels under a convention: voxel
// index x = u * scale - offset, clamped to [0, maxCoord], the cell's lower corner at most maxBase.
// GridSampler, the empty-space bricks and the Vulkan shaders all address the volume this way.
struct GridIndexing {
    glm::dvec3 scale{1.0}, offset{0.0};
    glm::dvec3 maxCoord{0.0};             // dims - 1
    glm::ivec3 maxBase{0};                // max(dims - 2, 0)
    std::int64_t stride[3] = {0, 0, 0};   // voxels; 0 along an axis of a single layer (both taps read it)

    GridIndexing() = default;
    GridIndexing(const glm::ivec3& dims, GridConvention convention) {
        const bool cell = convention == GridConvention::CellCentred;
        const std::int64_t strides[3] = {1, dims.x, std::int64_t(dims.x) * dims.y};
        for (int a = 0; a < 3; ++a) {
            scale[a] = cell ? dims[a] : dims[a] - 1;
            offset[a] = cell ? 0.5 : 0.0;
            maxCoord[a] = dims[a] - 1;
            maxBase[a] = std::max(dims[a] - 2, 0);
            stride[a] = dims[a] == 1 ? 0 : strides[a];
        }
    }
};

// What GridSampler reads besides the voxels, in its precision: the addressing of GridIndexing and the
// normalisation of the volume's range to s. The packet engine (simd_march.h) reads the same numbers.
template <class Real>
struct GridSamplerLayout {
    using Vec = glm::vec<3, Real>;

    GridSamplerLayout(const Volume& volume, GridConvention convention)
        : GridSamplerLayout(volume.dims, volume.normalisationRange(), convention) {}
    GridSamplerLayout(const glm::ivec3& dims, const ValueRange& r, GridConvention convention) {
        const GridIndexing g(dims, convention);
        scale = Vec(g.scale);
        offset = Vec(g.offset);
        for (int a = 0; a < 3; ++a) {
            maxCoord[a] = static_cast<Real>(g.maxCoord[a]);
            maxBase[a] = g.maxBase[a];
            stride[a] = g.stride[a];
        }
        lo = static_cast<Real>(r.lo);
        invRange = r.hi > r.lo ? static_cast<Real>(1.0 / (r.hi - r.lo)) : Real(0);
    }

    // The cell of the trilinear stencil at texture coordinate u: its lower corner voxel i and the
    // weights w of the upper corner along each axis.
    struct Cell {
        int i[3];
        Real w[3];
    };
    Cell cell(const Vec& u) const {
        const Vec x = u * scale - offset;  // continuous voxel index: voxel i sits at index i
        Cell c;
        for (int a = 0; a < 3; ++a) {
            // Clamp to the outermost voxels (texture "clamp to edge"); exact for node-centred data,
            // whose box ends on the outermost voxels anyway.
            const Real x0 = std::clamp(x[a], Real(0), maxCoord[a]);
            c.i[a] = std::min(static_cast<int>(x0), maxBase[a]);
            c.w[a] = x0 - static_cast<Real>(c.i[a]);
        }
        return c;
    }

    // The normalised scalar s interpolated from the cell's lower corner voxel p and its neighbours at
    // strides s (in voxels of T): the arithmetic every CPU sampler shares, so that they agree bit for bit.
    template <class T>
    Real interpolate(const T* p, const std::int64_t s[3], const Real w[3]) const {
        const std::int64_t sx = s[0], sy = s[1], sz = s[2];
        auto v = [p](std::int64_t o) { return static_cast<Real>(p[o]); };
        auto lerp = [](Real a, Real b, Real t) { return a + t * (b - a); };
        const Real c00 = lerp(v(0), v(sx), w[0]);
        const Real c10 = lerp(v(sy), v(sy + sx), w[0]);
        const Real c01 = lerp(v(sz), v(sz + sx), w[0]);
        const Real c11 = lerp(v(sz + sy), v(sz + sy + sx), w[0]);
        const Real c0 = lerp(c00, c10, w[1]);
        const Real c1 = lerp(c01, c11, w[1]);
        return (lerp(c0, c1, w[2]) - lo) * invRange;
    }

    Vec scale, offset;
    Real maxCoord[3];
    int maxBase[3];
    std::int64_t stride[3];
    Real lo, invRange;
};

template <class T, class Real>
class GridSampler {
public:
    using Vec = glm::vec<3, Real>;

    GridSampler(const Volume& volume, GridConvention convention) : data_(volume.data<T>()), g_(volume, convention) {}

    // Continuous voxel index of a texture coordinate: voxel i sits at index i.
    Vec index(const Vec& u) const { return u * g_.scale - g_.offset; }

    Real operator()(const Vec& u) const {
        const auto c = g_.cell(u);
        const std::int64_t base = c.i[0] * g_.stride[0] + c.i[1] * g_.stride[1] + c.i[2] * g_.stride[2];
        return g_.interpolate(data_ + base, g_.stride, c.w);
    }

private:
    const T* data_;
    GridSamplerLayout<Real> g_;
};

}  // namespace vri
