// The OpenEXR reader that replaced OpenImageIO for EXR files: an image must read exactly as OpenImageIO's
// module reads it (values, channel names, their order), whatever the file's layout.
#include <doctest/doctest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "temp_dir.h"
#include "libvri/io/image_io.h"
#include "libvri/io/io_module.h"
#include "libvri/io/oiio_module.h"
#include "libvri/util/error.h"

namespace {

namespace fs = std::filesystem;

vri::Image throughModule(const fs::path& path) {
    vri::Image image;
    vri::detail::requireModuleSuccess(vri::detail::oiioModule(path, "read image").readImage(path, image));
    return image;
}

bool sameImage(const vri::Image& a, const vri::Image& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           a.channelNames == b.channelNames && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// A file unlike vri's own: tiled, half floats, a data window away from the origin, and channels whose
// names sort differently from OpenImageIO's R, G, B, A first.
void writeForeignExr(const fs::path& path) {
    const Imath::Box2i window(Imath::V2i(3, 2), Imath::V2i(9, 6));  // 7 x 5 pixels
    Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(11, 8)), window);
    header.setTileDescription(Imf::TileDescription(4, 4));
    const std::vector<std::string> names = {"A", "B", "G", "R", "Z", "depth"};
    for (const std::string& name : names) header.channels().insert(name, Imf::Channel(Imf::HALF));
    const int width = 7, height = 5;
    std::vector<half> values(std::size_t(width) * height * names.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = half(float(i) * 0.37f - 20.0f);
    Imf::FrameBuffer frame;
    const std::size_t xStride = sizeof(half) * names.size(), yStride = xStride * width;
    for (std::size_t c = 0; c < names.size(); ++c)
        frame.insert(names[c], Imf::Slice(Imf::HALF,
                                          reinterpret_cast<char*>(values.data() + c) - 3 * xStride - 2 * yStride,
                                          xStride, yStride));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
}

}  // namespace

TEST_CASE("exr: a tiled half-float file with an offset data window reads as OpenImageIO reads it") {
    vri::test::TempDir dir("exr-file");
    writeForeignExr(dir / "foreign.exr");
    const vri::Image ours = vri::readImage(dir / "foreign.exr");
    CHECK(ours.width == 7);
    CHECK(ours.height == 5);
    CHECK(ours.channelNames == std::vector<std::string>{"R", "G", "B", "A", "Z", "depth"});
    CHECK(sameImage(ours, throughModule(dir / "foreign.exr")));
}

TEST_CASE("exr: vri's own files read the same both ways, metadata included") {
    vri::test::TempDir dir("exr-file");
    vri::Image image(4, 3, 6);
    image.channelNames = {"depth", "R", "A", "G", "B", "bound"};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) / 7.0f - 1e-30f;
    vri::writeExr(dir / "ours.exr", image, {{"vri:command", "vri-render -o 'a b.exr'"}});
    const vri::Image back = vri::readImage(dir / "ours.exr");
    CHECK(back.channelNames == std::vector<std::string>{"R", "G", "B", "A", "depth", "bound"});
    CHECK(sameImage(back, throughModule(dir / "ours.exr")));
    vri::ImageMetadata throughOiio;
    vri::detail::requireModuleSuccess(
        vri::detail::oiioModule(dir / "ours.exr", "read image").readImageMetadata(dir / "ours.exr", throughOiio));
    const vri::ImageMetadata ours = vri::readImageMetadata(dir / "ours.exr");
    CHECK(std::find(ours.begin(), ours.end(), std::pair<std::string, std::string>("vri:command",
                                                                                 "vri-render -o 'a b.exr'")) != ours.end());
    CHECK(std::find(throughOiio.begin(), throughOiio.end(),
                    std::pair<std::string, std::string>("vri:command", "vri-render -o 'a b.exr'")) != throughOiio.end());
}

TEST_CASE("exr: channels in OpenImageIO's order: layers by first channel, colour, alpha and depth first") {
    vri::test::TempDir dir("exr-file");
    // Each list as the file sorts it, and as OpenImageIO 2.4 read it back (measured with its Python module).
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        {{"Z", "Y", "real", "imag", "zz", "a", "r"}, {"r", "Y", "real", "imag", "a", "Z", "zz"}},
        {{"Alpha", "Red", "Green", "Blue", "x"}, {"Red", "Green", "Blue", "Alpha", "x"}},
        {{"l.R", "l.G", "R", "G", "B", "A", "m.A", "m.R", "depth", "Depth"},
         {"R", "G", "B", "A", "Depth", "depth", "l.R", "l.G", "m.R", "m.A"}},
        {{"AR", "RA", "AB", "BA", "AG", "GA", "Zback", "Z", "Y"}, {"Y", "AR", "RA", "AG", "GA", "AB", "BA", "Z", "Zback"}},
        {{"foo", "Bar", "baz", "_x", "1"}, {"1", "Bar", "_x", "baz", "foo"}},
        {{"a.b.R", "a.R", "a.b.A", "a-x.R", "a.G", "b.R"}, {"a-x.R", "a.R", "a.G", "a.b.R", "a.b.A", "b.R"}},
        {{"B", "Y", "G", "imag", "Alpha", "ZBack", "zback", "DEPTH", "RED"},
         {"RED", "G", "B", "Y", "imag", "Alpha", "DEPTH", "ZBack", "zback"}}};
    for (const auto& [names, expected] : cases) {
        vri::Image image(1, 1, int(names.size()));
        image.channelNames = names;
        vri::writeExr(dir / "order.exr", image);
        CHECK(vri::readImage(dir / "order.exr").channelNames == expected);
        CHECK(throughModule(dir / "order.exr").channelNames == expected);
    }
}

TEST_CASE("exr: a truncated file is one line naming it") {
    vri::test::TempDir dir("exr-file");
    vri::Image image(16, 16);
    vri::writeExr(dir / "whole.exr", image);
    std::ifstream in(dir / "whole.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir / "cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    try {
        vri::readImage(dir / "cut.exr");
        FAIL("a truncated EXR was read");
    } catch (const vri::Error& e) {
        const std::string message = e.what();
        CHECK(message.starts_with((dir / "cut.exr").string() + ": cannot read image: "));
        CHECK(message.find('\n') == std::string::npos);
    }
}
