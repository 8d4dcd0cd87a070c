// Sizes from input: checked products and limits, and the messages that name what was asked for.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>

#include "scoped_environment.h"
#include "libvri/core/camera.h"
#include "libvri/core/image.h"
#include "libvri/core/volume.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

// VRI_MAX_BYTES for one test, what was there restored after.
struct ByteLimitOverride : vri::test::ScopedEnvironment {
    explicit ByteLimitOverride(const char* value) : ScopedEnvironment("VRI_MAX_BYTES", std::string(value)) {}
};

constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

}  // namespace

TEST_CASE("checked size: products that fit are exact, products that wrap are detected") {
    CHECK(checkedProduct({}) == 1u);
    CHECK(checkedProduct({256, 256, 256, 4}) == 67108864u);
    CHECK(checkedProduct({kMax, 1}) == kMax);
    CHECK(checkedProduct({std::uint64_t(1) << 32, std::uint64_t(1) << 32}) == std::nullopt);
    // The issue's .vdb: 4194304 x 4194304 x 1048576 voxels wrap to exactly 0 in 64 bits.
    CHECK(checkedProduct({4194304, 4194304, 1048576}) == std::nullopt);
    CHECK(checkedProduct({kMax, kMax, 0}) == 0u);  // a zero factor wins, wherever it is
}

TEST_CASE("checked size: a count over its limit names the input, the count and the limit") {
    CHECK(checkedCount("runs", {10, 10}, 100, "runs") == 100u);
    CHECK_THROWS_WITH_AS(checkedCount("the sweep", {10, 11}, 100, "runs"), "the sweep: needs 110 runs, limit 100",
                         Error);
    CHECK_THROWS_WITH_AS(checkedCount("x", {kMax, 2}, 100, "rows"), "x: needs about 3.69e+19 rows, limit 100", Error);
}

TEST_CASE("checked size: bytes are limited to 2^34 unless VRI_MAX_BYTES says otherwise") {
    if (!std::getenv("VRI_MAX_BYTES")) {
        CHECK(byteLimit() == kDefaultByteLimit);
        CHECK(checkedBytes("b", {std::uint64_t(1) << 30, 16}) == std::size_t(1) << 34);
        CHECK_THROWS_WITH_AS(checkedBytes("b", {(std::uint64_t(1) << 34) + 1}),
                             "b: needs 17179869185 bytes, limit 17179869184 (VRI_MAX_BYTES)", Error);
    }
    {
        const ByteLimitOverride limit("1000");
        CHECK(byteLimitIsExplicit());
        CHECK(checkedBytes("b", {10, 100}) == 1000u);
        CHECK_THROWS_WITH_AS(checkedBytes("b", {1001}), "b: needs 1001 bytes, limit 1000 (VRI_MAX_BYTES)", Error);
    }
    for (const char* bad : {"", "0", "-5", "12k", "1e9", "99999999999999999999999"}) {
        const ByteLimitOverride limit(bad);
        CHECK_THROWS_WITH_AS(byteLimit(), doctest::Contains("VRI_MAX_BYTES: expected a positive byte count"), Error);
    }
}

TEST_CASE("checked size: work estimated in floating point") {
    CHECK_NOTHROW(requireWithin("w", 1e9, 1e9, "samples"));
    CHECK_THROWS_WITH_AS(requireWithin("w", 2e9, 1e9, "samples"), "w: needs 2000000000 samples, limit 1000000000",
                         Error);
    CHECK_THROWS_WITH_AS(requireWithin("w", 1e300, 1e9, "samples"), "w: needs about 1e+300 samples, limit 1000000000",
                         Error);
    CHECK_THROWS_WITH_AS(requireWithin("w", std::numeric_limits<double>::infinity(), 1e9, "samples"),
                         doctest::Contains("unboundedly many"), Error);
    CHECK_THROWS_AS(requireWithin("w", std::numeric_limits<double>::quiet_NaN(), 1e9, "samples"), Error);
}

TEST_CASE("checked size: unpacked bytes within a ratio of what they unpack from, or 256 MiB") {
    if (!std::getenv("VRI_MAX_BYTES")) {
        CHECK(checkedUnpackedBytes("v", {1024, 1024, 256}, 12, "compressed data", 256) == kAlwaysPlausibleBytes);
        CHECK_THROWS_WITH_AS(checkedUnpackedBytes("v", {1024, 1024, 257}, 12, "compressed data", 256),
                             "v: needs 269484032 bytes, limit 268435456 for compressed data of 12 bytes (256 times its "
                             "size or 256 MiB; set VRI_MAX_BYTES to allow more)",
                             Error);
        // Past the floor the ratio rules: 2 MB compressed may unpack to 512 MB, not 513.
        CHECK(checkedUnpackedBytes("v", {512000000}, 2000000, "a file", 256) == 512000000u);
        CHECK_THROWS_WITH_AS(checkedUnpackedBytes("v", {512000001}, 2000000, "a file", 256),
                             doctest::Contains("v: needs 512000001 bytes, limit 512000000 for a file of 2000000 bytes"),
                             Error);
        CHECK(checkedUnpackedBytes("v", {1024000000}, 1000000, "a file", 1024) == 1024000000u);
        // A packed size whose ratio would wrap is no limit but the byte limit's.
        CHECK(checkedUnpackedBytes("v", {std::uint64_t(1) << 34}, kMax, "a file", 1024) == std::size_t(1) << 34);
        CHECK_THROWS_WITH_AS(checkedUnpackedBytes("v", {std::uint64_t(1) << 35}, kMax, "a file", 1024),
                             "v: needs 34359738368 bytes, limit 17179869184 (VRI_MAX_BYTES)", Error);
    }
    // A stated limit is the only one.
    const ByteLimitOverride limit("1000000000");
    CHECK(checkedUnpackedBytes("v", {1000000000}, 1, "compressed data", 256) == 1000000000u);
    CHECK_THROWS_WITH_AS(checkedUnpackedBytes("v", {1000000001}, 1, "compressed data", 256),
                         "v: needs 1000000001 bytes, limit 1000000000 (VRI_MAX_BYTES)", Error);
}

TEST_CASE("checked size: volumes and images refuse sizes that wrap or exceed the limit before allocating") {
    CHECK_THROWS_WITH_AS(Volume(glm::ivec3(2097152, 2097152, 4194304), VoxelType::Float32),
                         "a 2097152x2097152x4194304 float32 volume: needs about 7.38e+19 bytes, limit 17179869184 "
                         "(VRI_MAX_BYTES)",
                         Error);
    CHECK_THROWS_WITH_AS(Image(100000, 100000), doctest::Contains("needs 160000000000 bytes"), Error);
    CHECK_THROWS_WITH_AS(Image(2000000000, 2000000000), doctest::Contains("needs about 6.4e+19 bytes"), Error);
    const ByteLimitOverride limit("4096");
    CHECK(Volume(glm::ivec3(16, 16, 8), VoxelType::UInt16).bytes.size() == 4096u);
    CHECK_THROWS_WITH_AS(Volume(glm::ivec3(16, 16, 9), VoxelType::UInt16), doctest::Contains("limit 4096"), Error);
    CHECK(Image(16, 16).pixels.size() == 1024u);
    CHECK_THROWS_AS(Image(16, 17), Error);
}

TEST_CASE("camera: messages say what is wrong with extreme coordinates") {
    CameraSpec spec;
    spec.width = spec.height = 8;
    spec.eye = {1e308, 0.0, 0.0};
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("camera eye 1e+308,0,0: coordinates must be finite"), Error);
    spec.eye = {0.0, 0.0, 5.0};
    spec.target = {0.0, std::numeric_limits<double>::infinity(), 0.0};
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("camera target"), Error);
    // A scene 1e-300 across: squaring underflows, yet the eye and target do not coincide.
    spec.eye = {0.0, 0.0, 3e-300};
    spec.target = {0.0, 0.0, 0.0};
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("only 3e-300 apart"), Error);
    spec.eye = spec.target;
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("coincide"), Error);
    spec.eye = {0.0, 0.0, 5.0};
    spec.up = {0.0, 0.0, 0.0};
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("up vector 0,0,0 is zero"), Error);
    spec.up = {0.0, 0.0, 1.0};
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("parallel"), Error);
    // Tiny and huge scenes within the bounds still get a camera, looking the same way.
    spec.up = {0.0, 1e-100, 0.0};
    spec.eye = {0.0, 0.0, 1e-100};
    const Camera tiny(spec);
    spec.up = {0.0, 1.0, 0.0};
    spec.eye = {0.0, 0.0, 1e100};
    const Camera huge(spec);
    CHECK(tiny.direction(3, 4) == huge.direction(3, 4));
    spec.width = 100000;
    spec.height = 100000;
    CHECK_THROWS_WITH_AS(Camera{spec}, doctest::Contains("needs 160000000000 bytes"), Error);
}
