// Difference heat maps with a numbered colour bar.
#include "libvri/core/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "libvri/core/image_compare.h"
#include "libvri/core/number_glyphs.h"
#include "libvri/util/error.h"
#include "libvri/util/parse.h"

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

constexpr int kGap = 4, kBar = 12, kTicks = 6, kLabelGap = 2, kMargin = 2;
constexpr std::array<double, 3> kClipped{1.0, 0.0, 1.0};  // magenta: above the top of the scale

// Where an error sits on the scale, 0 (bottom) to 1 (top); above 1 when it is clipped.
double positionOf(double e, const HeatMapScale& scale) {
    if (!scale.log) return e / scale.top;
    if (!(e > 0)) return 0.0;
    return std::max(0.0, 1.0 + std::log10(e / scale.top) / scale.decades);
}

struct Tick {
    double at;  // 0 to 1 along the bar
    std::string label;
};

std::string numberLabel(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", value);
    return text;
}

// Linear: quarters of the scale, 0 first; log: each decade, top / 10^decades first.
std::vector<Tick> ticksOf(const HeatMapScale& scale) {
    std::vector<Tick> ticks;
    if (!scale.log) {
        for (int q = 0; q <= 4; ++q) ticks.push_back({q / 4.0, q == 0 ? "0" : numberLabel(scale.top * q / 4.0)});
    } else {
        for (int d = 0; d <= scale.decades; ++d)
            ticks.push_back({double(d) / scale.decades, numberLabel(scale.top * std::pow(10.0, d - scale.decades))});
    }
    return ticks;
}

// The left edge of a label centred on the tick at x, kept on the canvas.
int labelLeft(int x, int width, int canvasWidth) { return std::clamp(x - width / 2, 0, std::max(0, canvasWidth - width)); }

int tickX(int canvasWidth, double at) { return static_cast<int>(std::floor((canvasWidth - 1) * at)); }

// The space that keeps two labels apart: two characters' advance, so that "0" and "0.25" never read
// as "00.25".
int labelSpace(int scale) { return 2 * (kGlyphColumns + 1) * scale; }

// The ticks whose labels stand labelSpace apart on a canvas `canvasWidth` wide: all, else every other one
// (both ends kept), else the two ends; empty when not even those two fit.
std::vector<Tick> labelledTicks(const std::vector<Tick>& ticks, int canvasWidth, int scale) {
    std::vector<Tick> everyOther, ends{ticks.front(), ticks.back()};
    for (std::size_t i = 0; i < ticks.size(); i += 2) everyOther.push_back(ticks[i]);
    if (everyOther.back().at != ticks.back().at) everyOther.push_back(ticks.back());
    for (const std::vector<Tick>& candidate : {ticks, everyOther, ends}) {
        bool apart = true;
        int right = -labelSpace(scale);  // the previous label's right edge
        for (const Tick& t : candidate) {
            const int width = numberTextWidth(t.label, scale);
            const int left = labelLeft(tickX(canvasWidth, t.at), width, canvasWidth);
            apart = apart && left >= right + labelSpace(scale);
            right = left + width;
        }
        if (apart) return candidate;
    }
    return {};
}

}  // namespace

std::optional<int> heatScaleDecades(std::string_view text) {
    if (text == "linear") return 0;
    if (text == "log") return 3;
    if (!text.starts_with("log:")) return std::nullopt;
    const std::optional<std::int64_t> n = integerFromText(text.substr(4));
    if (!n || *n < 1 || *n > 12) return std::nullopt;
    return static_cast<int>(*n);
}

int heatMapLabelScale(int canvasWidth) { return canvasWidth >= 256 ? 2 : 1; }

Image heatMapImage(const Image& a, const Image& b, const HeatMapScale& scale) {
    if (!(scale.top > 0) || !std::isfinite(scale.top))
        throw Error("heat map: the top of the scale must be a positive number");
    if (scale.log && (scale.decades < 1 || scale.decades > 12))
        throw Error("heat map: a log scale spans 1 to 12 decades, got " + std::to_string(scale.decades));
    const Image difference = differenceImage(a, b);
    const std::vector<Tick> ticks = ticksOf(scale);

    // A canvas wide enough for the labels of both ends, labelSpace apart.
    int canvasWidth = a.width;
    if (labelledTicks(ticks, canvasWidth, heatMapLabelScale(canvasWidth)).empty()) {
        const int cell = heatMapLabelScale(canvasWidth);
        canvasWidth = numberTextWidth(ticks.front().label, cell) + numberTextWidth(ticks.back().label, cell) +
                      labelSpace(cell);
    }
    const int cell = heatMapLabelScale(canvasWidth);
    const int barRows = kGap + kBar + kTicks + kLabelGap + kGlyphRows * cell + kMargin;
    Image heat(canvasWidth, a.height + barRows, 4);
    for (int y = 0; y < heat.height; ++y)
        for (int x = 0; x < heat.width; ++x) paint(heat, x, y, {1.0, 1.0, 1.0});

    const int left = (canvasWidth - a.width) / 2;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double e = 0;
            for (int c = 0; c < a.channels; ++c) e = std::max(e, double(difference.pixels[(std::size_t(y) * a.width + x) * a.channels + c]));
            const double u = positionOf(e, scale);
            paint(heat, left + x, y, u > 1.0 ? kClipped : viridis(u));
        }
    const int barTop = a.height + kGap;
    for (int x = 0; x < canvasWidth; ++x) {
        const auto colour = viridis(canvasWidth > 1 ? double(x) / double(canvasWidth - 1) : 0.0);
        for (int y = barTop; y < barTop + kBar; ++y) paint(heat, x, y, colour);
    }
    for (const Tick& t : ticks)
        for (int y = barTop + kBar; y < barTop + kBar + kTicks; ++y) paint(heat, tickX(canvasWidth, t.at), y, {0.0, 0.0, 0.0});
    const int labelTop = barTop + kBar + kTicks + kLabelGap;
    for (const Tick& t : labelledTicks(ticks, canvasWidth, cell)) {
        const int width = numberTextWidth(t.label, cell);
        drawNumberText(heat, labelLeft(tickX(canvasWidth, t.at), width, canvasWidth), labelTop, cell, t.label,
                       {0.0f, 0.0f, 0.0f, 1.0f});
    }
    return heat;
}

}  // namespace vri
