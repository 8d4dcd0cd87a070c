#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "libvri/core/out_of_range_pixels.h"

TEST_CASE("out-of-range pixels: counted per pixel and per channel, with the extremes") {
    vri::Image image(3, 1);
    const float values[] = {0.5f, 1.0f, 0.0f, 1.0f,                                         // in range, edges included
                            1.25f, 0.2f, 1.0001f, 1.0f,                                     // two channels above 1
                            -0.5f, std::numeric_limits<float>::quiet_NaN(), 0.3f, 0.9f};  // one below 0, NaN left out
    std::copy(std::begin(values), std::end(values), image.pixels.begin());
    const vri::OutOfRangePixels found = vri::findOutOfRangePixels(image);
    CHECK(found.pixels == 2);
    CHECK(found.channelsAbove == 2);
    CHECK(found.channelsBelow == 1);
    CHECK(found.max == 1.25f);
    CHECK(found.min == -0.5f);

    const vri::OutOfRangePixels none = vri::findOutOfRangePixels(vri::Image(2, 2));
    CHECK(none.pixels == 0);
    CHECK(none.max == 0.0f);
    CHECK(none.min == 0.0f);
}

TEST_CASE("out-of-range pixels: colour and alpha only, not a brick layer's place along the rays") {
    vri::Image layer(1, 1, 5);
    layer.channelNames[4] = "brick_order";
    const float values[] = {0.5f, 0.25f, 0.125f, 0.75f, 3.0f};
    std::copy(std::begin(values), std::end(values), layer.pixels.begin());
    CHECK(vri::findOutOfRangePixels(layer).pixels == 0);
    CHECK(vri::findOutOfRangePixels(layer).max == 0.75f);
}

TEST_CASE("clampToUnitRange: every channel into [0, 1], NaN left as it is") {
    vri::Image image(2, 1);
    const float values[] = {1.5f, -0.25f, 0.5f, 1.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 2.0f, 0.75f};
    std::copy(std::begin(values), std::end(values), image.pixels.begin());
    vri::clampToUnitRange(image);
    const float expected[] = {1.0f, 0.0f, 0.5f, 1.0f, 0.0f, 0.0f, 1.0f, 0.75f};
    for (int i = 0; i < 8; ++i)
        if (i == 5) CHECK(std::isnan(image.pixels[i]));
        else CHECK(image.pixels[i] == expected[i]);
    CHECK(vri::findOutOfRangePixels(image).pixels == 0);
}
