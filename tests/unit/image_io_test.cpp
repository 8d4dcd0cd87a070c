#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "file_bytes.h"
#include "temp_dir.h"
#include "libvri/io/image_io.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"

namespace {

namespace fs = std::filesystem;
using vri::test::readBytes;

// Values a float format must keep bit for bit: fractions with no short decimal form, a denormal,
// negative zero, huge, tiny and infinite values.
vri::Image awkwardImage() {
    vri::Image image(5, 3);
    const float values[] = {1.0f / 3, -0.0f, std::numeric_limits<float>::denorm_min(), 3.0e38f, -7.25f,
                            1e-30f, std::numeric_limits<float>::infinity(), 0.1f, 0.7f, 2.0f};
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = values[i % std::size(values)] * static_cast<float>(1 + i / std::size(values));
    return image;
}

bool bitIdentical(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Reads a PNG preview back as bytes (readImage gives byte / 255).
std::vector<int> previewBytes(const fs::path& path) {
    const vri::Image png = vri::readImage(path);
    REQUIRE(png.channels == 3);
    std::vector<int> bytes;
    for (float v : png.pixels) bytes.push_back(static_cast<int>(std::lround(v * 255.0f)));
    return bytes;
}

vri::Image onePixel(float r, float g, float b, float a) {
    vri::Image image(1, 1);
    image.pixels = {r, g, b, a};
    return image;
}

}  // namespace

TEST_CASE("image: OpenEXR round trip is bit exact in float, names and metadata kept") {
    vri::test::TempDir dir("image-io");
    const vri::Image image = awkwardImage();
    vri::writeExr(dir / "render.exr", image, {{"vri:method", "riemann h=0.5"}, {"vri:commit", "abc123"}});
    const vri::Image back = vri::readImage(dir / "render.exr");
    CHECK(back.width == 5);
    CHECK(back.height == 3);
    CHECK(back.channelNames == std::vector<std::string>{"R", "G", "B", "A"});
    CHECK(bitIdentical(back.pixels, image.pixels));

    const vri::ImageMetadata metadata = vri::readImageMetadata(dir / "render.exr");
    const auto has = [&](const std::string& name, const std::string& value) {
        return std::find(metadata.begin(), metadata.end(), std::pair{name, value}) != metadata.end();
    };
    CHECK(has("vri:method", "riemann h=0.5"));
    CHECK(has("vri:commit", "abc123"));
}

TEST_CASE("image: single-channel EXR keeps its name, writeExr ignores the extension") {
    vri::test::TempDir dir("image-io");
    vri::Image depth(3, 2, 1);
    depth.channelNames = {"Z"};
    depth.pixels = {0.5f, 1.5f, 2.5f, -1.0f, 1e-7f, 42.0f};
    vri::writeExr(dir / "depth.data", depth);
    CHECK(readBytes(dir / "depth.data").substr(0, 4) == "\x76\x2f\x31\x01");  // OpenEXR magic number
    const vri::Image back = vri::readImage(dir / "depth.data");
    CHECK(back.channelNames == std::vector<std::string>{"Z"});
    CHECK(bitIdentical(back.pixels, depth.pixels));
}

TEST_CASE("image: writeImage picks the format from the extension") {
    vri::test::TempDir dir("image-io");
    const vri::Image image = awkwardImage();
    vri::writeImage(dir / "a.EXR", image);
    CHECK(bitIdentical(vri::readImage(dir / "a.EXR").pixels, image.pixels));
    vri::writeImage(dir / "a.tif", image);  // TIFF stores float too
    CHECK(bitIdentical(vri::readImage(dir / "a.tif").pixels, image.pixels));
    vri::writeImage(dir / "a.png", image);
    CHECK(vri::readImage(dir / "a.png").channels == 3);
    CHECK_THROWS_WITH_AS(vri::writeImage(dir / "a.nosuchformat", image),
                         doctest::Contains("a.nosuchformat: cannot write image"), vri::Error);
    // SGI cannot be encoded into memory, so its writes could not all be checked.
    CHECK_THROWS_WITH_AS(vri::writeImage(dir / "a.sgi", image), doctest::Contains("a.sgi: cannot write sgi images"),
                         vri::Error);
    CHECK_FALSE(fs::exists(dir / "a.sgi"));
}

TEST_CASE("image: PNG preview composites premultiplied colour over the background, encodes sRGB, rounds to nearest") {
    vri::test::TempDir dir("image-io");
    SUBCASE("opaque pixels: sRGB(0.5) = 0.7354 -> 187.5 rounds up to 188, 0.25 -> 0.5371 -> 137, above 1 clamps") {
        vri::writePng(dir / "p.png", onePixel(0.5f, 0.25f, 1.5f, 1.0f));
        CHECK(previewBytes(dir / "p.png") == std::vector<int>{188, 137, 255});
    }
    SUBCASE("half transparent over a coloured background: c + (1 - A) * bg") {
        vri::PngOptions options;
        options.background = {1.0f, 0.5f, 0.0f};
        vri::writePng(dir / "p.png", onePixel(0.25f, 0.0f, 0.5f, 0.5f), options);
        // 0.75 -> sRGB 0.8808 -> 225, 0.25 -> 137, 0.5 -> 188
        CHECK(previewBytes(dir / "p.png") == std::vector<int>{225, 137, 188});
    }
    SUBCASE("exposure, then invert, then clamp") {
        vri::PngOptions options;
        options.exposure = 2.0f;
        options.invert = true;
        vri::writePng(dir / "p.png", onePixel(0.25f, 0.125f, 0.75f, 1.0f), options);
        // x2 -> 0.5, 0.25, 1.5; inverted -> 0.5, 0.75, -0.5
        CHECK(previewBytes(dir / "p.png") == std::vector<int>{188, 225, 0});
    }
    SUBCASE("NaN shows as 0, negative clamps to 0") {
        vri::writePng(dir / "p.png", onePixel(std::nanf(""), -3.0f, 0.0f, 1.0f));
        CHECK(previewBytes(dir / "p.png") == std::vector<int>{0, 0, 0});
    }
    SUBCASE("a single channel becomes grey") {
        vri::Image grey(2, 1, 1);
        grey.channelNames = {"Y"};
        grey.pixels = {0.25f, 1.0f};
        vri::writePng(dir / "p.png", grey);
        CHECK(previewBytes(dir / "p.png") == std::vector<int>{137, 137, 137, 255, 255, 255});
    }
}

TEST_CASE("image: reading errors are one line and name the file") {
    vri::test::TempDir dir("image-io");
    const std::string missing = (dir / "missing.exr").string() + ": no such file";
    CHECK_THROWS_WITH_AS(vri::readImage(dir / "missing.exr"), missing.c_str(), vri::Error);
    std::ofstream(dir / "garbage.exr") << "not an image\nat all\n";
    try {
        vri::readImage(dir / "garbage.exr");
        FAIL("garbage read as an image");
    } catch (const vri::Error& e) {
        const std::string message = e.what();
        CHECK(message.starts_with((dir / "garbage.exr").string() + ": cannot read image: "));
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("image: a failed write leaves the old file intact and no temporary file behind") {
    vri::test::TempDir dir("image-io");
    const fs::path target = dir / "render.exr";
    vri::writeExr(target, awkwardImage());
    const std::string before = readBytes(target);

    vri::Image broken = awkwardImage();
    broken.pixels.pop_back();  // inconsistent: would read past the pixel array
    CHECK_THROWS_AS(vri::writeExr(target, broken), vri::Error);
    CHECK_THROWS_AS(vri::writeAtomically(target,
                                         [](const fs::path& tmp) {
                                             std::ofstream(tmp) << "half written";
                                             throw vri::Error("interrupted");
                                         }),
                    vri::Error);

    CHECK(readBytes(target) == before);
    CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator{}) == 1);
}
