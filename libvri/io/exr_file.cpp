#include "libvri/io/exr_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVersion.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <string_view>
#include <utility>

#include "libvri/util/error.h"
#include "libvri/util/printable.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// OpenEXR writes through an output stream; this one keeps the bytes, seekable as the library needs.
class MemoryStream final : public Imf::OStream {
public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char data[], int n) override {
        if (position + n > bytes.size()) bytes.resize(position + n);
        std::memcpy(bytes.data() + position, data, n);
        position += n;
    }
    uint64_t tellp() override { return position; }
    void seekp(uint64_t to) override { position = to; }
    std::string bytes;

private:
    std::size_t position = 0;
};

// OpenImageIO's channel order, which every reader of vri's images has relied on (measured with its
// Python module on 2.4): channels grouped by layer (the name up to its last '.'), the layers in the order
// of their first channel in the file's sorted list; within a layer the colour, alpha and depth channels
// first, in the rank below (names compared without case), then the rest, ties in the file's order.
std::vector<std::string> channelOrder(const Imf::ChannelList& channels) {
    static constexpr std::array<std::array<std::string_view, 2>, 15> kRanked = {{{"r", "red"}, {"g", "green"},
        {"b", "blue"}, {"y", ""}, {"real", ""}, {"imag", ""}, {"a", "alpha"}, {"ar", ""}, {"ra", ""}, {"ag", ""},
        {"ga", ""}, {"ab", ""}, {"ba", ""}, {"z", "depth"}, {"zback", ""}}};
    const auto rank = [](std::string_view name) {
        std::string suffix(name.substr(name.find_last_of('.') + 1));  // npos + 1 == 0: the whole name
        std::transform(suffix.begin(), suffix.end(), suffix.begin(), [](unsigned char c) { return std::tolower(c); });
        for (std::size_t i = 0; i < kRanked.size(); ++i)
            if (suffix == kRanked[i][0] || suffix == kRanked[i][1]) return i;
        return kRanked.size();
    };
    const auto layerOf = [](std::string_view name) {
        const std::size_t dot = name.find_last_of('.');
        return std::string(dot == std::string_view::npos ? std::string_view() : name.substr(0, dot));
    };
    std::vector<std::string> names, layers;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        names.emplace_back(it.name());
        if (std::find(layers.begin(), layers.end(), layerOf(it.name())) == layers.end())
            layers.push_back(layerOf(it.name()));
    }
    const auto key = [&](const std::string& name) {
        return std::pair(std::find(layers.begin(), layers.end(), layerOf(name)) - layers.begin(), rank(name));
    };
    std::stable_sort(names.begin(), names.end(),
                     [&](const std::string& a, const std::string& b) { return key(a) < key(b); });
    return names;
}

[[noreturn]] void cannotRead(const fs::path& path, const std::exception& e) {
    throw Error(path.string() + ": cannot read image: " + oneLine(e.what()));
}

}  // namespace

bool isExrFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::array<char, 4> magic{};
    return in.read(magic.data(), magic.size()) && Imf::isImfMagic(magic.data());
}

Image readExrFile(const fs::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
        const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
        const std::vector<std::string> names = channelOrder(file.header().channels());
        if (width < 1 || height < 1 || width > std::numeric_limits<int>::max() ||
            height > std::numeric_limits<int>::max() || names.empty())
            throw Error(path.string() + ": cannot read image: data window of " + std::to_string(width) + "x" +
                        std::to_string(height) + " pixels with " + std::to_string(names.size()) + " channels");
        Image image;
        try {
            image = Image(int(width), int(height), int(names.size()));  // the header's size, checked before allocating
        } catch (const Error& e) {
            throw Error(path.string() + ": " + e.what());
        }
        image.channelNames = names;
        // Slices address pixel (x, y) of the data window at base + x * xStride + y * yStride, so the base is
        // shifted back by the window's corner (OpenEXR's convention; the pointer itself is never dereferenced).
        const std::size_t xStride = sizeof(float) * names.size();
        const std::size_t yStride = xStride * std::size_t(width);
        Imf::FrameBuffer frame;
        for (std::size_t c = 0; c < names.size(); ++c) {
            char* base = reinterpret_cast<char*>(image.pixels.data() + c) -
                         std::ptrdiff_t(window.min.x) * std::ptrdiff_t(xStride) -
                         std::ptrdiff_t(window.min.y) * std::ptrdiff_t(yStride);
            frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, xStride, yStride));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        cannotRead(path, e);
    }
}

ImageMetadata readExrMetadata(const fs::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        ImageMetadata metadata;
        for (auto it = file.header().begin(); it != file.header().end(); ++it)
            if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                metadata.emplace_back(it.name(), text->value());
        return metadata;
    } catch (const std::exception& e) {
        cannotRead(path, e);
    }
}

std::string encodeExr(const Image& image, const ImageMetadata& metadata) {
    Imf::Header header(image.width, image.height, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                       Imf::ZIP_COMPRESSION);
    for (const auto& [name, value] : metadata) header.insert(name, Imf::StringAttribute(value));
    const std::size_t xStride = sizeof(float) * image.channels;
    const std::size_t yStride = xStride * image.width;
    Imf::FrameBuffer frame;
    for (int c = 0; c < image.channels; ++c) {
        header.channels().insert(image.channelNames[c], Imf::Channel(Imf::FLOAT));
        frame.insert(image.channelNames[c],
                     Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data() + c)),
                                xStride, yStride));
    }
    MemoryStream memory;
    {
        Imf::OutputFile file(memory, header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    }  // the file is complete (its offset table written) only once closed
    return std::move(memory.bytes);
}

}  // namespace vri::detail
