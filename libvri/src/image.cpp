#include "vri/image.h"

#include "vri/error.h"

namespace vri {

Image::Image(int w, int h, int n) : width(w), height(h), channels(n) {
    if (w <= 0 || h <= 0)
        throw Error("image size must be positive, got " + std::to_string(w) + "x" + std::to_string(h));
    if (n <= 0) throw Error("image must have at least one channel");
    static const char* names[] = {"R", "G", "B", "A"};
    channelNames.clear();
    for (int c = 0; c < n; ++c) channelNames.push_back(c < 4 ? names[c] : "C" + std::to_string(c));
    pixels.assign(static_cast<std::size_t>(w) * h * n, 0.0f);
}

}  // namespace vri
