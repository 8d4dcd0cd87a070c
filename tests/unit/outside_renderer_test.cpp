// The outside-renderer plumbing (outside_renderer.h) and the image helpers it reads with (image.h): the
// placeholders of a renderer's command, the raw .f32 image, the channels an image must have, and the flip.
#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <vector>

#include "libvri/core/image.h"
#include "libvri/render/outside_renderer.h"
#include "libvri/util/error.h"
#include "temp_dir.h"

using vri::Error;
using vri::Image;

TEST_CASE("outside renderer: placeholders are filled in, braces escaped, unknown and unclosed ones refused") {
    const std::map<std::string, std::string, std::less<>> values{{"card", "/w/card.json"}, {"step", "0.5"}};
    CHECK(vri::expandPlaceholders({"r", "--scene={card}", "{step}{step}", "{{literal}}", "plain"}, values) ==
          std::vector<std::string>{"r", "--scene=/w/card.json", "0.50.5", "{literal}", "plain"});
    CHECK_THROWS_WITH_AS(vri::expandPlaceholders({"{output}"}, values),
                         "renderer command word '{output}': unknown placeholder {output} (expected {card}, {step})", Error);
    CHECK_THROWS_WITH_AS(vri::expandPlaceholders({"x{card"}, values),
                         "renderer command word 'x{card': a '{' without its '}' (write {{)", Error);
    CHECK_THROWS_WITH_AS(vri::expandPlaceholders({"x}"}, values),
                         "renderer command word 'x}': a '}' without its '{' (write }})", Error);
}

TEST_CASE("outside renderer: a raw .f32 image is read as RGBA rows from the top, and its size is checked") {
    vri::test::TempDir dir("outside");
    const std::vector<float> values{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f};  // 1 x 2, two pixels
    {
        std::ofstream out(dir / "image.f32", std::ios::binary);
        out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * 4));
    }
    std::string quantisation;
    const Image image = vri::readOutsideImage(dir / "image.f32", 1, 2, quantisation);
    CHECK(quantisation == "float32");
    CHECK(image.pixels == values);
    CHECK(image.at(0, 1, 0) == 0.5f);  // the second row
    CHECK_THROWS_WITH_AS(vri::readOutsideImage(dir / "image.f32", 2, 2, quantisation),
                         ((dir / "image.f32").string() + ": 32 bytes, expected 64 (float32 RGBA, 2x2)").c_str(), Error);
    CHECK_THROWS_WITH_AS(vri::readOutsideImage(dir / "none.exr", 1, 2, quantisation),
                         ((dir / "none.exr").string() + ": the renderer wrote no image there").c_str(), Error);
}

TEST_CASE("image: channels selected by name, and rows flipped") {
    Image rgb(2, 2, 3);
    for (std::size_t i = 0; i < rgb.pixels.size(); ++i) rgb.pixels[i] = static_cast<float>(i);
    const Image gr = vri::selectChannels(rgb, {"G", "R"}, "x.exr");
    CHECK(gr.channelNames == std::vector<std::string>{"G", "R"});
    CHECK(gr.at(1, 0, 0) == rgb.at(1, 0, 1));
    CHECK(gr.at(1, 0, 1) == rgb.at(1, 0, 0));
    CHECK_THROWS_WITH_AS(vri::selectChannels(rgb, {"R", "A"}, "x.exr"), "x.exr: no channel 'A' (it has R,G,B)", Error);
    const Image flipped = vri::flippedVertically(rgb);
    CHECK(flipped.at(0, 0, 2) == rgb.at(0, 1, 2));
    CHECK(vri::flippedVertically(flipped).pixels == rgb.pixels);
}
