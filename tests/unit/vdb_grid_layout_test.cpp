#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "libvri/io/vdb_grid_layout.h"
#include "libvri/util/error.h"

using vri::detail::VdbGridFacts;
using vri::detail::VdbValueType;
using vri::detail::vdbVolumeLayout;

namespace {

VdbGridFacts grid(VdbValueType valueType) {
    VdbGridFacts facts;
    facts.description = "grid 'density' (test)";
    facts.valueType = valueType;
    return facts;
}

VdbGridFacts writtenByVri(const char* type, glm::ivec3 dims, VdbValueType valueType) {
    VdbGridFacts facts = grid(valueType);
    facts.voxelTypeMeta = type;
    facts.dimsMeta = dims;
    return facts;
}

VdbGridFacts foreign(glm::ivec3 min, glm::ivec3 max, VdbValueType valueType = VdbValueType::Float) {
    VdbGridFacts facts = grid(valueType);
    facts.activeMin = min;
    facts.activeMax = max;
    return facts;
}

void requireRefused(const VdbGridFacts& facts, const std::string& expected) {
    try {
        vdbVolumeLayout("g.vdb", facts);
        FAIL("accepted a grid that should be refused: " << expected);
    } catch (const vri::Error& e) {
        const std::string message = e.what();
        CHECK_MESSAGE(message.find(expected) != std::string::npos, message);
        CHECK(message.rfind("g.vdb: ", 0) == 0);
    }
}

}  // namespace

TEST_CASE("vdbVolumeLayout: a grid written by vri keeps its type, dense dims and range") {
    VdbGridFacts facts = writtenByVri("uint16", {256, 256, 113}, VdbValueType::Int32);
    facts.rangeMeta = glm::dvec2(0.0, 4095.0);
    facts.activeMin = glm::ivec3(3, 3, 3);  // trailing empty slabs: the metadata's dims win
    facts.activeMax = glm::ivec3(10, 10, 10);
    const auto layout = vdbVolumeLayout("g.vdb", facts);
    CHECK(layout.type == vri::VoxelType::UInt16);
    CHECK(layout.boxMin == glm::ivec3(0, 0, 0));
    CHECK(layout.dims == glm::ivec3(256, 256, 113));
    REQUIRE(layout.range);
    CHECK(layout.range->hi == 4095.0);
}

TEST_CASE("vdbVolumeLayout: any other grid is float32 over its active voxels, without vri's range") {
    VdbGridFacts facts = foreign({-3, -2, -1}, {4, 5, 6}, VdbValueType::Double);
    facts.rangeMeta = glm::dvec2(0.0, 1.0);  // without vri's type and dims the range is not vri's
    facts.linear = glm::dmat3(0.5);
    const auto layout = vdbVolumeLayout("g.vdb", facts);
    CHECK(layout.type == vri::VoxelType::Float32);
    CHECK(layout.boxMin == glm::ivec3(-3, -2, -1));
    CHECK(layout.dims == glm::ivec3(8, 8, 8));
    CHECK_FALSE(layout.range);
    // A single active voxel is a 1x1x1 volume.
    CHECK(vdbVolumeLayout("g.vdb", foreign({7, 7, 7}, {7, 7, 7})).dims == glm::ivec3(1, 1, 1));
}

TEST_CASE("vdbVolumeLayout: transforms other than a positive axis-aligned scale are refused") {
    VdbGridFacts rotated = foreign({0, 0, 0}, {7, 7, 7});
    rotated.linear = glm::dmat3(0, 1, 0, 1, 0, 0, 0, 0, 1);
    requireRefused(rotated, "rotated, flipped or non-linear transform");
    VdbGridFacts flipped = foreign({0, 0, 0}, {7, 7, 7});
    flipped.linear[1][1] = -1.0;
    requireRefused(flipped, "rotated, flipped or non-linear transform");
    VdbGridFacts notANumber = foreign({0, 0, 0}, {7, 7, 7});
    notANumber.linear[2][2] = std::numeric_limits<double>::quiet_NaN();
    requireRefused(notANumber, "rotated, flipped or non-linear transform");
    VdbGridFacts nonlinear = foreign({0, 0, 0}, {7, 7, 7});
    nonlinear.linearTransform = false;
    requireRefused(nonlinear, "rotated, flipped or non-linear transform");
    // OpenVDB's tolerance: off-diagonal rounding up to 1e-15 in all is still axis-aligned.
    VdbGridFacts rounded = foreign({0, 0, 0}, {7, 7, 7});
    rounded.linear[0][1] = 1e-16;
    CHECK(vdbVolumeLayout("g.vdb", rounded).dims == glm::ivec3(8, 8, 8));
    rounded.linear[0][1] = 1e-14;
    requireRefused(rounded, "rotated, flipped or non-linear transform");
}

TEST_CASE("vdbVolumeLayout: version 2 keeps every voxel type in a FloatGrid indexed at voxel centres") {
    VdbGridFacts facts = writtenByVri("uint8", {4, 3, 2}, VdbValueType::Float);
    facts.formatVersionMeta = vri::detail::kVdbFormatVersion;
    const auto layout = vdbVolumeLayout("g.vdb", facts);
    CHECK(layout.type == vri::VoxelType::UInt8);
    CHECK(layout.indexAtVoxelCentres);
    // Version 1 (no vri_format_version): uint8 in an Int32Grid, index at the box corner.
    CHECK_FALSE(vdbVolumeLayout("g.vdb", writtenByVri("uint8", {4, 3, 2}, VdbValueType::Int32)).indexAtVoxelCentres);
    // Other programs' grids: OpenVDB's meaning, whatever the value type.
    CHECK(vdbVolumeLayout("g.vdb", foreign({0, 0, 0}, {1, 1, 1}, VdbValueType::Int64)).indexAtVoxelCentres);
    facts.valueType = VdbValueType::Int32;
    requireRefused(facts, "cannot hold uint8 voxels");
    facts.formatVersionMeta = 3;
    requireRefused(facts, "vri_format_version 3");
}

TEST_CASE("vdbVolumeLayout: metadata that do not fit the grid are refused before anything is allocated") {
    requireRefused(writtenByVri("uint8", {8, 8, 8}, VdbValueType::Float), "cannot hold uint8 voxels");
    requireRefused(writtenByVri("float32", {8, 8, 8}, VdbValueType::Int32), "cannot hold float32 voxels");
    requireRefused(writtenByVri("float64", {8, 8, 8}, VdbValueType::Int32), "vri_voxel_type");
    requireRefused(writtenByVri("uint8", {0, 8, 8}, VdbValueType::Int32), "vri_dims must be positive");
    VdbGridFacts empty = foreign({0, 0, 0}, {0, 0, 0});
    empty.activeMin.reset();
    empty.activeMax.reset();
    requireRefused(empty, "has no active voxels");
    // 2^32 voxels wide: more than an int (and OpenVDB's coordinates) can count.
    requireRefused(foreign({std::numeric_limits<int>::min(), 0, 0}, {std::numeric_limits<int>::max(), 0, 0}),
                   "more than a volume can hold");
}
