// Trilinear reconstruction in both grid conventions.
#include <doctest/doctest.h>

#include <random>

#include "libvri/core/analytic_field.h"
#include "libvri/core/grid_sampler.h"

using namespace vri;
using V = glm::dvec3;

TEST_CASE("node-centred trilinear sampling reproduces a linear field exactly") {
    // f = (x + 2y + 4z) / 64 on a 5x4x3 grid: every node value is exact in float.
    Volume v({5, 4, 3}, VoxelType::Float32);
    v.range = ValueRange{0.0, 1.0};
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 5; ++x) v.data<float>()[v.index(x, y, z)] = float(x + 2 * y + 4 * z) / 64.0f;
    const GridSampler<float, double> sample(v, GridConvention::NodeCentred);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
        const V u(u01(rng), u01(rng), u01(rng));
        const V idx = u * V(4.0, 3.0, 2.0);  // node convention: index = u * (n - 1)
        CHECK(sample(u) == doctest::Approx((idx.x + 2 * idx.y + 4 * idx.z) / 64.0).epsilon(1e-14));
    }
    // The box corners are voxels.
    CHECK(sample(V(0.0)) == 0.0);
    CHECK(sample(V(1.0)) == doctest::Approx((4 + 6 + 8) / 64.0).epsilon(1e-15));
}

TEST_CASE("paper A's linear field sampled onto a node grid is reproduced exactly") {
    const LinearField field;  // (x + 1.5) / 3 on [-1.5, 1.5]^3, 5^3 grid
    const Volume grid = sampleOntoGrid(field, GridConvention::NodeCentred);
    CHECK(grid.spacing.x == 0.75);
    CHECK(volumeBox(grid, GridConvention::NodeCentred).lo.x == -1.5);
    CHECK(volumeBox(grid, GridConvention::NodeCentred).hi.x == 1.5);
    const GridSampler<float, double> sample(grid, GridConvention::NodeCentred);
    for (double x : {0.0, 0.1, 0.37, 0.5, 0.93, 1.0})
        CHECK(sample(V(x, 0.3, 0.8)) == doctest::Approx(x).epsilon(1e-15));
}

TEST_CASE("cell-centred sampling clamps to the edge voxels outside the outermost centres") {
    Volume v({4, 1, 1}, VoxelType::UInt8);
    for (int x = 0; x < 4; ++x) v.data<std::uint8_t>()[x] = static_cast<std::uint8_t>(10 * x + 10);  // 10..40
    const GridSampler<std::uint8_t, double> sample(v, GridConvention::CellCentred);
    const auto s = [](double raw) { return raw / 255.0; };
    CHECK(sample(V(0.0, 0.5, 0.5)) == doctest::Approx(s(10)));        // box face: clamped to voxel 0
    CHECK(sample(V(0.1, 0.5, 0.5)) == doctest::Approx(s(10)));        // still before the first centre
    CHECK(sample(V(0.125, 0.5, 0.5)) == doctest::Approx(s(10)));      // the first centre
    CHECK(sample(V(0.25, 0.5, 0.5)) == doctest::Approx(s(15)));       // halfway to the second
    CHECK(sample(V(0.875, 0.5, 0.5)) == doctest::Approx(s(40)));      // the last centre
    CHECK(sample(V(1.0, 0.5, 0.5)) == doctest::Approx(s(40)));        // clamped
    // The same data node-centred: the box ends on the outermost voxels, nothing is clamped inside.
    const GridSampler<std::uint8_t, double> node(v, GridConvention::NodeCentred);
    CHECK(node(V(0.0, 0.5, 0.5)) == doctest::Approx(s(10)));
    CHECK(node(V(0.5, 0.5, 0.5)) == doctest::Approx(s(25)));
}

TEST_CASE("samplers keep native types: uint16 normalised by its full range, float by the set range") {
    Volume v({2, 2, 2}, VoxelType::UInt16);
    for (std::size_t i = 0; i < 8; ++i) v.data<std::uint16_t>()[i] = 65535;
    CHECK(GridSampler<std::uint16_t, float>(v, GridConvention::CellCentred)(glm::vec3(0.3f)) == 1.0f);
    v.range = ValueRange{0.0, 131070.0};
    CHECK(GridSampler<std::uint16_t, double>(v, GridConvention::CellCentred)(V(0.3)) == 0.5);
}
