#include <doctest/doctest.h>

#include "libvri/core/volume_stats.h"
#include "libvri/util/error.h"

TEST_CASE("volume stats: mean, zeros and a histogram over the type's range") {
    vri::Volume volume({4, 1, 1}, vri::VoxelType::UInt8);
    std::uint8_t* v = volume.data<std::uint8_t>();
    v[0] = 0;
    v[1] = 0;
    v[2] = 100;
    v[3] = 255;
    const vri::VolumeStats stats = vri::computeVolumeStats(volume, 16);
    CHECK(stats.data == vri::ValueRange{0, 255});
    CHECK(stats.normalisation == vri::ValueRange{0, 255});
    CHECK(stats.mean == doctest::Approx(355.0 / 4));
    CHECK(stats.zeroFraction == 0.5);
    REQUIRE(stats.histogram.size() == 16);
    CHECK(stats.histogram[0] == 2);
    CHECK(stats.histogram[6] == 1);   // 100 / (255 / 16) = 6.27
    CHECK(stats.histogram[15] == 1);  // the range's top value falls in the last bin
    CHECK(stats.below + stats.above == 0);
}

TEST_CASE("volume stats: values outside the volume's own range are counted apart") {
    vri::Volume volume({3, 1, 1}, vri::VoxelType::Float32);
    float* v = volume.data<float>();
    v[0] = -1.0f;
    v[1] = 0.5f;
    v[2] = 3.0f;
    volume.range = vri::ValueRange{0.0, 1.0};
    const vri::VolumeStats stats = vri::computeVolumeStats(volume, 2);
    CHECK(stats.below == 1);
    CHECK(stats.above == 1);
    CHECK(stats.histogram == std::vector<std::uint64_t>{0, 1});
    CHECK_THROWS_AS(vri::computeVolumeStats(volume, 0), vri::Error);
}
