// SparseVolume: the bricks kept, the voxel values, the sampler, the empty-space grid, the stats and whole
// images are those of the dense volume it came from, bit for bit, for every voxel type, both conventions and
// sizes that are no multiple of the brick.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include "same_bits.h"
#include "test_camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/sparse_sampler.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/core/volume_stats.h"

using namespace vri;

namespace {

// Zero but for a few blobs of noise (so whole bricks are empty, others full, others touched at an edge), and
// for float a negative blob and a -0.0 voxel alone in its brick.
std::shared_ptr<Volume> blobs(glm::ivec3 dims, VoxelType type) {
    auto v = std::make_shared<Volume>(dims, type);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    const glm::dvec3 centres[] = {glm::dvec3(0.2, 0.3, 0.25) * glm::dvec3(dims), glm::dvec3(0.7, 0.6, 0.8) * glm::dvec3(dims),
                                  glm::dvec3(dims) - glm::dvec3(1.0)};
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                double value = 0.0;
                for (const glm::dvec3& c : centres) {
                    const glm::dvec3 d = glm::dvec3(x, y, z) - c;
                    if (d.x * d.x + d.y * d.y + d.z * d.z < 9.0) value = 10.0 + 200.0 * u01(rng);
                }
                const std::size_t i = v->index(x, y, z);
                dispatchVoxelType(type, [&](auto t) {
                    using T = decltype(t);
                    const bool negative = std::is_same_v<T, float> && x < dims.x / 2;
                    v->data<T>()[i] = static_cast<T>(negative ? -value : value);
                });
            }
    if (type == VoxelType::Float32 && dims.x > 12 && dims.y > 12 && dims.z > 12)
        v->data<float>()[v->index(12, 12, 12)] = -0.0f;
    return v;
}

TransferFunction visibleAbove(double s) {
    return TransferFunction({{0.0, 0.0, 0.0, 0.0, 0.0}, {s, 0.8, 0.5, 0.2, 0.0}, {1.0, 0.9, 0.3, 0.1, 2.0}},
                            EmissionModel::ColourTimesExtinction);
}

template <class T, class Real>
void checkSamples(const Volume& dense, const SparseVolume& sparse, GridConvention convention) {
    const GridSampler<T, Real> a(dense, convention);
    const SparseGridSampler<T, Real> b(sparse, convention);
    std::mt19937 rng(3);
    std::uniform_real_distribution<Real> u(Real(-0.05), Real(1.05));  // outside the box too: clamped alike
    for (int i = 0; i < 20000; ++i) {
        const glm::vec<3, Real> p(u(rng), u(rng), u(rng));
        const Real x = a(p), y = b(p);
        REQUIRE(std::memcmp(&x, &y, sizeof(Real)) == 0);
    }
}

}  // namespace

TEST_CASE("a sparse copy keeps the voxels, samples and empty-space grid of the dense volume bit for bit") {
    for (const VoxelType type : {VoxelType::UInt8, VoxelType::UInt16, VoxelType::Float32})
        for (const glm::ivec3 dims : {glm::ivec3(29, 23, 17), glm::ivec3(16, 8, 24), glm::ivec3(21, 1, 9),
                                      glm::ivec3(1, 1, 1)}) {
            CAPTURE(voxelTypeName(type));
            const int dx = dims.x, dy = dims.y, dz = dims.z;
            CAPTURE(dx);
            CAPTURE(dy);
            CAPTURE(dz);
            const auto dense = blobs(dims, type);
            if (type == VoxelType::UInt16) dense->range = ValueRange{5.0, 300.0};
            const SparseVolume sparse = SparseVolume::fromDense(*dense);
            CHECK(sparse.dims == dense->dims);
            CHECK(sparse.range == dense->range);
            CHECK(sparse.background() == 0.0);
            CHECK(sparse.storedBricks() <= sparse.brickCount());
            for (int z = 0; z < dims.z; ++z)
                for (int y = 0; y < dims.y; ++y)
                    for (int x = 0; x < dims.x; ++x) {
                        const double a = dense->value(x, y, z), b = sparse.value(x, y, z);
                        REQUIRE(std::memcmp(&a, &b, sizeof a) == 0);
                    }
            CHECK(sparse.dataRange() == dense->dataRange());
            CHECK(sparse.normalisationRange() == dense->normalisationRange());
            for (const GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred}) {
                if (convention == GridConvention::NodeCentred && glm::any(glm::lessThan(dims, glm::ivec3(2)))) continue;
                dispatchVoxelType(type, [&](auto t) {
                    checkSamples<decltype(t), double>(*dense, sparse, convention);
                    checkSamples<decltype(t), float>(*dense, sparse, convention);
                });
                for (const double s : {0.0, 0.05, 0.5}) {
                    const OccupancyGrid a(*dense, convention, visibleAbove(s)), b(sparse, convention, visibleAbove(s));
                    CHECK(a.emptyFlags() == b.emptyFlags());
                }
            }
            const VolumeStats a = computeVolumeStats(*dense), b = computeVolumeStats(sparse);
            CHECK(a.data == b.data);
            CHECK(a.normalisation == b.normalisation);
            CHECK(a.mean == doctest::Approx(b.mean).epsilon(1e-12));
            CHECK(a.zeroFraction == b.zeroFraction);
            CHECK(a.activeVoxels == b.activeVoxels);
            CHECK(a.bricks == b.bricks);
            CHECK(a.activeBricks == b.activeBricks);
            CHECK(a.histogram == b.histogram);
            CHECK(a.below == b.below);
            CHECK(a.above == b.above);
        }
}

TEST_CASE("a sparse volume stores only the bricks whose block (the brick and its apron) is not all background") {
    Volume dense(glm::ivec3(32, 16, 16), VoxelType::UInt8);
    dense.data<std::uint8_t>()[dense.index(8, 0, 0)] = 7;  // first voxel of brick (1,0,0): in brick 0's apron too
    dense.data<std::uint8_t>()[dense.index(30, 15, 15)] = 9;
    const SparseVolume sparse = SparseVolume::fromDense(dense);
    CHECK(sparse.bricks() == glm::ivec3(4, 2, 2));
    CHECK(sparse.storedBricks() == 3);
    CHECK(sparse.table()[sparse.brickIndex(0, 0, 0)] != 0);
    CHECK(sparse.table()[sparse.brickIndex(1, 0, 0)] != 0);
    CHECK(sparse.table()[sparse.brickIndex(3, 1, 1)] != 0);
    CHECK(sparse.table()[sparse.brickIndex(2, 0, 0)] == 0);
    CHECK(sparse.byteCount() == 16 * sizeof(std::uint32_t) + 4 * SparseVolume::kBlockVoxels);  // 3 and the background
    CHECK(sparse.value(8, 0, 0) == 7.0);
    CHECK(sparse.value(20, 5, 5) == 0.0);
}

TEST_CASE("a sparse scene renders the dense scene's image bit for bit with every method") {
    const auto dense = blobs(glm::ivec3(29, 23, 17), VoxelType::UInt8);
    const auto sparse = std::make_shared<SparseVolume>(SparseVolume::fromDense(*dense));
    const CameraSpec spec = test::cameraSpec(glm::dvec3(-20.0, 35.0, -40.0), glm::dvec3(14.5, 11.5, 8.5), 40.0, 31, 19);
    const Camera camera(spec);
    for (const Integrator integrator :
         {Integrator::Riemann, Integrator::Composite, Integrator::Simpson, Integrator::Coupled, Integrator::Decoupled})
        for (const Precision precision : {Precision::Double, Precision::Float})
            for (const GridConvention convention : {GridConvention::CellCentred, GridConvention::NodeCentred}) {
                RenderOptions options;
                options.integrator = integrator;
                options.precision = precision;
                options.samplingRate = 3.0;
                const Scene a{dense, std::nullopt, convention, visibleAbove(0.05)};
                const Scene b{nullptr, std::nullopt, convention, visibleAbove(0.05), sparse};
                CHECK(a.box().lo == b.box().lo);
                CHECK(a.box().hi == b.box().hi);
                RenderStats sa, sb, sc;
                CHECK(test::sameBits(render(a, camera, options, &sa), render(b, camera, options, &sb)));
                options.simd = false;  // the packet engine counts the samples of its packets' lanes its own way
                CHECK(test::sameBits(render(a, camera, options, &sa), render(b, camera, options, &sc)));
                CHECK(sa.samplesEvaluated == sb.samplesEvaluated);
                CHECK(sc.samplesEvaluated == sb.samplesEvaluated);
                CHECK(sa.emptyBrickFraction == sb.emptyBrickFraction);
                CHECK(sb.simdTarget.empty());  // the scalar path, whatever RenderOptions::simd says
            }
}
