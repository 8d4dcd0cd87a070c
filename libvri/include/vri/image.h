#pragma once
// A float image with interleaved channels (RGBA for renders), row 0 at the top.
#include <cstddef>
#include <string>
#include <vector>

namespace vri {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;
    std::vector<std::string> channelNames{"R", "G", "B", "A"};
    std::vector<float> pixels;  // width * height * channels

    Image() = default;
    // Zero-filled RGBA image (or `n` channels named R, G, B, A, then C4, ...); throws vri::Error on a zero size.
    Image(int w, int h, int n = 4);

    float& at(int x, int y, int c) { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

}  // namespace vri
