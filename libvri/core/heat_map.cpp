// Difference heat maps with a colour bar.
#include "libvri/core/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "libvri/core/image_compare.h"
#include "libvri/util/error.h"

namespace vri {

namespace {

// Viridis in sRGB at 9 evenly spaced stops (matplotlib's table sampled at 0, 1/8, ..., 1); between
// stops the colour is interpolated linearly in sRGB, close enough to the 256-entry table for a figure.
constexpr std::array<std::array<double, 3>, 9> kViridis{{{0.267, 0.005, 0.329},
                                                        {0.283, 0.141, 0.458},
                                                        {0.254, 0.265, 0.530},
                                                        {0.207, 0.372, 0.553},
                                                        {0.164, 0.471, 0.558},
                                                        {0.128, 0.567, 0.551},
                                                        {0.135, 0.659, 0.518},
                                                        {0.267, 0.749, 0.441},
                                                        {0.478, 0.821, 0.318}}};
constexpr std::array<double, 3> kViridisTop{0.993, 0.906, 0.144};

// The sRGB colour at u in [0, 1]: the 9 stops above and the map's last colour (yellow) at 1.
std::array<double, 3> viridis(double u) {
    u = std::clamp(u, 0.0, 1.0);
    const double at = u * double(kViridis.size());  // 9 intervals: the stops, then the top colour
    const std::size_t i = std::min(static_cast<std::size_t>(at), kViridis.size() - 1);
    const auto& lo = kViridis[i];
    const auto& hi = i + 1 < kViridis.size() ? kViridis[i + 1] : kViridisTop;
    const double f = at - double(i);
    return {lo[0] + f * (hi[0] - lo[0]), lo[1] + f * (hi[1] - lo[1]), lo[2] + f * (hi[2] - lo[2])};
}

// IEC 61966-2-1's decoding: the linear value whose sRGB encoding is `v`, so that the preview writer's
// encoding gives back the colour map's bytes.
float linearOf(double v) {
    return static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

void paint(Image& image, int x, int y, const std::array<double, 3>& srgb) {
    for (int c = 0; c < 3; ++c) image.at(x, y, c) = linearOf(srgb[c]);
    image.at(x, y, 3) = 1.0f;
}

}  // namespace

Image heatMapImage(const Image& a, const Image& b, double top) {
    if (!(top > 0) || !std::isfinite(top)) throw Error("heat map: the top of the scale must be a positive number");
    const Image difference = differenceImage(a, b);
    Image heat(a.width, a.height + kHeatMapBarRows, 4);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double e = 0;
            for (int c = 0; c < a.channels; ++c) e = std::max(e, double(difference.pixels[(std::size_t(y) * a.width + x) * a.channels + c]));
            paint(heat, x, y, viridis(e / top));
        }
    const int gap = 4, bar = 12;
    for (int y = a.height; y < heat.height; ++y)
        for (int x = 0; x < a.width; ++x) paint(heat, x, y, {1.0, 1.0, 1.0});
    for (int x = 0; x < a.width; ++x) {
        const auto colour = viridis(a.width > 1 ? double(x) / double(a.width - 1) : 0.0);
        for (int y = a.height + gap; y < a.height + gap + bar; ++y) paint(heat, x, y, colour);
    }
    for (int quarter = 0; quarter <= 4; ++quarter) {
        const int x = std::min(a.width - 1, (a.width - 1) * quarter / 4);
        for (int y = a.height + gap + bar; y < heat.height - 2; ++y) paint(heat, x, y, {0.0, 0.0, 0.0});
    }
    return heat;
}

}  // namespace vri
