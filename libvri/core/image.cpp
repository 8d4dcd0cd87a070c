#include "libvri/core/image.h"

#include <algorithm>
#include <cstdint>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri {

std::size_t imageBytes(int w, int h, int n) {
    if (w <= 0 || h <= 0)
        throw Error("image size must be positive, got " + std::to_string(w) + "x" + std::to_string(h));
    if (n <= 0) throw Error("image must have at least one channel");
    return checkedBytes("a " + std::to_string(w) + "x" + std::to_string(h) + " image of " + std::to_string(n) +
                            " float channels",
                        {std::uint64_t(w), std::uint64_t(h), std::uint64_t(n), sizeof(float)});
}

Image::Image(int w, int h, int n) : width(w), height(h), channels(n) {
    const std::size_t bytes = imageBytes(w, h, n);
    static const char* names[] = {"R", "G", "B", "A"};
    channelNames.clear();
    for (int c = 0; c < n; ++c) channelNames.push_back(c < 4 ? names[c] : "C" + std::to_string(c));
    allocateOrExplain("a " + std::to_string(w) + "x" + std::to_string(h) + " image", bytes,
                      [&] { pixels.assign(bytes / sizeof(float), 0.0f); });
}

bool PixelRegion::inside(int w, int h) const {
    return x >= 0 && y >= 0 && width >= 1 && height >= 1 && std::int64_t(x) + width <= w &&
           std::int64_t(y) + height <= h;
}

std::string PixelRegion::text() const {
    return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(width) + "," + std::to_string(height);
}

int channelIndex(const Image& image, std::string_view name) {
    const auto it = std::find(image.channelNames.begin(), image.channelNames.end(), name);
    return it == image.channelNames.end() ? -1 : static_cast<int>(it - image.channelNames.begin());
}

Image flippedVertically(const Image& image) {
    Image out = image;
    const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
    for (std::size_t y = 0; y < static_cast<std::size_t>(image.height); ++y)
        std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row), row,
                    out.pixels.begin() + static_cast<std::ptrdiff_t>((image.height - 1 - y) * row));
    return out;
}

Image selectChannels(const Image& image, const std::vector<std::string>& names, const std::string& what) {
    std::vector<int> from;
    for (const std::string& name : names) {
        const int c = channelIndex(image, name);
        if (c < 0) {
            std::string has;
            for (const std::string& n : image.channelNames) has += (has.empty() ? "" : ",") + n;
            throw Error(what + ": no channel '" + name + "' (it has " + has + ")");
        }
        from.push_back(c);
    }
    Image out(image.width, image.height, static_cast<int>(names.size()));
    out.channelNames = names;
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < from.size(); ++c)
            out.pixels[p * from.size() + c] = image.pixels[p * image.channels + from[c]];
    return out;
}

}  // namespace vri
