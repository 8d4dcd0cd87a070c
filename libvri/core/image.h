#pragma once
// A float image with interleaved channels (RGBA for renders), row 0 at the top.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace vri {

// The bytes of a w x h float image of n channels; throws vri::Error on a size that is not positive or
// whose bytes exceed byteLimit() (checked_size.h). Callers that size other buffers per pixel check
// with it before they allocate.
std::size_t imageBytes(int w, int h, int n = 4);

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;
    std::vector<std::string> channelNames{"R", "G", "B", "A"};
    std::vector<float> pixels;  // width * height * channels

    Image() = default;
    // Zero-filled RGBA image (or `n` channels named R, G, B, A, then C4, ...); throws vri::Error on a zero
    // size or one whose pixels exceed imageBytes()' limit.
    Image(int w, int h, int n = 4);

    float& at(int x, int y, int c) { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

// A rectangle of an image's pixels, in the pixel coordinates of the whole image (x to the right, y down
// from row 0 at the top, as Image::at and Camera::direction count them): the part of an image a render
// computes when it is asked for a region (--region), and where a tile of a merged image goes.
struct PixelRegion {
    int x = 0, y = 0, width = 0, height = 0;

    static PixelRegion whole(int w, int h) { return {0, 0, w, h}; }
    // True when it has pixels and lies inside a w x h image (summed in 64 bits: no overflow).
    bool inside(int w, int h) const;
    bool contains(int px, int py) const { return px >= x && py >= y && px - x < width && py - y < height; }
    std::string text() const;  // "X,Y,W,H", as --region spells it
    bool operator==(const PixelRegion&) const = default;
};

// The index of the channel called `name`, or -1 when the image has none.
int channelIndex(const Image& image, std::string_view name);

// The image with its rows in reverse order: row 0 becomes the bottom row.
Image flippedVertically(const Image& image);

// The channels called `names`, in that order; throws vri::Error "<what>: no channel '<name>' (it has ...)".
Image selectChannels(const Image& image, const std::vector<std::string>& names, const std::string& what);

}  // namespace vri
