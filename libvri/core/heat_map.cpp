// Difference heat maps with a numbered colour bar.
#include "libvri/core/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "libvri/core/image_compare.h"
#include "libvri/core/text_glyphs.h"
#include "libvri/util/checked_size.h"
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
// Black on a signed map, where magenta would read as its red end: beyond -top or +top (or NaN).
constexpr std::array<double, 3> kSignedClipped{0.0, 0.0, 0.0};

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
            const int width = glyphTextWidth(t.label, scale);
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

std::optional<double> heatTopPercentile(std::string_view text) {
    if (text == "max") return 100.0;
    // Decimal only ("p99.5", "p1e-3"): no hexadecimal, no blanks, no sign.
    if (!text.starts_with("p") || text.size() < 2 || text.find_first_not_of("0123456789.eE-", 1) != std::string_view::npos ||
        text[1] == '-')
        return std::nullopt;
    const std::optional<double> n = numberFromText(text.substr(1));
    if (!n || !(*n > 0) || *n > 100) return std::nullopt;
    return *n;
}

double heatMapTop(const Image& a, const std::vector<const Image*>& set, double percentile, const PixelMask* mask) {
    std::vector<float> errors;
    for (const Image* x : set) {
        requireSameShape(a, *x);
        for (std::size_t p = 0; p < std::size_t(a.width) * std::size_t(a.height); ++p) {
            if (mask && !mask->keep[p]) continue;
            double e = 0;
            for (std::size_t i = p * std::size_t(a.channels); i < (p + 1) * std::size_t(a.channels); ++i)
                e = std::max(e, absoluteError(a.pixels[i], x->pixels[i]));
            if (e > 0) errors.push_back(static_cast<float>(e));
        }
    }
    if (errors.empty()) return 0.0;
    // Nearest rank: the smallest error at or above `percentile` % of them.
    const std::size_t rank = std::min(errors.size() - 1,
                                      static_cast<std::size_t>(std::ceil(percentile / 100.0 * double(errors.size()))) - 1);
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(rank), errors.end());
    return errors[rank];
}

namespace {

constexpr int kTitleTop = 2, kTitleGap = 4;

int titleRows(const std::string& title, int cell) { return title.empty() ? 0 : kTitleTop + kGlyphRows * cell + kTitleGap; }

// The title at the canvas' top left, a cell in, cut to its width with "..".
void drawTitle(Image& canvas, const std::string& title, int cell) {
    if (title.empty()) return;
    std::string text = title;
    if (glyphTextWidth(text, cell) > canvas.width - 2 * cell) {
        while (!text.empty() && glyphTextWidth(text + "..", cell) > canvas.width - 2 * cell) text.pop_back();
        text += "..";
    }
    drawGlyphText(canvas, cell, kTitleTop, cell, text, {0.0f, 0.0f, 0.0f, 1.0f});
}

// A canvas mapWidth wide, or wider when the bar's end labels need it (labelSpace apart).
int canvasWidthFor(int mapWidth, const std::vector<Tick>& ticks) {
    if (!labelledTicks(ticks, mapWidth, heatMapLabelScale(mapWidth)).empty()) return mapWidth;
    const int cell = heatMapLabelScale(mapWidth);
    return glyphTextWidth(ticks.front().label, cell) + glyphTextWidth(ticks.back().label, cell) + labelSpace(cell);
}

// A white canvas for a map mapHeight high: the title's rows, the map, the bar's.
Image whiteCanvas(int width, int mapHeight, int titleHeight) {
    const int cell = heatMapLabelScale(width);
    Image canvas(width, titleHeight + mapHeight + kGap + kBar + kTicks + kLabelGap + kGlyphRows * cell + kMargin, 4);
    for (int y = 0; y < canvas.height; ++y)
        for (int x = 0; x < canvas.width; ++x) paint(canvas, x, y, {1.0, 1.0, 1.0});
    return canvas;
}

// The colour bar from barTop down: colourAt(u) from the left edge (u = 0) to the right (u = 1), the ticks
// and their labels.
template <typename ColourAt>
void drawBar(Image& canvas, int barTop, const std::vector<Tick>& ticks, ColourAt colourAt) {
    const int cell = heatMapLabelScale(canvas.width);
    for (int x = 0; x < canvas.width; ++x) {
        const auto colour = colourAt(canvas.width > 1 ? double(x) / double(canvas.width - 1) : 0.0);
        for (int y = barTop; y < barTop + kBar; ++y) paint(canvas, x, y, colour);
    }
    for (const Tick& t : ticks)
        for (int y = barTop + kBar; y < barTop + kBar + kTicks; ++y) paint(canvas, tickX(canvas.width, t.at), y, {0.0, 0.0, 0.0});
    const int labelTop = barTop + kBar + kTicks + kLabelGap;
    for (const Tick& t : labelledTicks(ticks, canvas.width, cell)) {
        const int width = glyphTextWidth(t.label, cell);
        drawGlyphText(canvas, labelLeft(tickX(canvas.width, t.at), width, canvas.width), labelTop, cell, t.label,
                      {0.0f, 0.0f, 0.0f, 1.0f});
    }
}

// Moreland's cool-warm diverging map in sRGB, its ends and its light grey middle (not the canvas' white, so
// that a map's edge shows where it has no error): the signed maps' colours, interpolated in sRGB.
constexpr std::array<double, 3> kCool{0.230, 0.299, 0.754}, kMiddle{0.865, 0.865, 0.865}, kWarm{0.706, 0.016, 0.150};

std::array<double, 3> coolWarm(double u) {  // u in [0, 1], 0.5 the middle
    const double f = std::clamp(std::abs(2.0 * u - 1.0), 0.0, 1.0);
    const auto& end = u < 0.5 ? kCool : kWarm;
    return {kMiddle[0] + f * (end[0] - kMiddle[0]), kMiddle[1] + f * (end[1] - kMiddle[1]),
            kMiddle[2] + f * (end[2] - kMiddle[2])};
}

}  // namespace

Image heatMapImage(const Image& a, const Image& b, const HeatMapScale& scale, const std::string& title) {
    if (!(scale.top > 0) || !std::isfinite(scale.top))
        throw Error("heat map: the top of the scale must be a positive number");
    if (scale.log && (scale.decades < 1 || scale.decades > 12))
        throw Error("heat map: a log scale spans 1 to 12 decades, got " + std::to_string(scale.decades));
    const Image difference = differenceImage(a, b);
    const std::vector<Tick> ticks = ticksOf(scale);
    const int canvasWidth = canvasWidthFor(a.width, ticks);
    const int mapTop = titleRows(title, heatMapLabelScale(canvasWidth));
    Image heat = whiteCanvas(canvasWidth, a.height, mapTop);
    drawTitle(heat, title, heatMapLabelScale(canvasWidth));
    const int left = (canvasWidth - a.width) / 2;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double e = 0;
            for (int c = 0; c < a.channels; ++c) e = std::max(e, double(difference.pixels[(std::size_t(y) * a.width + x) * a.channels + c]));
            const double u = positionOf(e, scale);
            paint(heat, left + x, mapTop + y, u > 1.0 ? kClipped : viridis(u));
        }
    drawBar(heat, mapTop + a.height + kGap, ticks, viridis);
    return heat;
}

Image signedHeatMapImage(const Image& a, const Image& b, double top, const std::string& title) {
    if (!(top > 0) || !std::isfinite(top)) throw Error("heat map: the top of the scale must be a positive number");
    requireSameShape(a, b);
    constexpr int kBetween = 8;
    const int mapsWidth = static_cast<int>(checkedCount("signed heat map", {std::uint64_t(a.channels), std::uint64_t(a.width) + kBetween},
                                                        std::uint64_t(1) << 20, "pixels wide")) - kBetween;
    const std::vector<Tick> ticks{{0.0, "-" + numberLabel(top)}, {0.5, "0"}, {1.0, numberLabel(top)}};
    const int canvasWidth = canvasWidthFor(mapsWidth, ticks);
    const int cell = heatMapLabelScale(canvasWidth);
    const int mapTop = titleRows(title, cell), namesRows = kTitleTop + kGlyphRows * cell;
    Image heat = whiteCanvas(canvasWidth, a.height + namesRows, mapTop);
    drawTitle(heat, title, cell);
    for (int c = 0; c < a.channels; ++c) {
        const int left = (canvasWidth - mapsWidth) / 2 + c * (a.width + kBetween);
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                const double d = double(b.at(x, y, c)) - double(a.at(x, y, c));
                const double u = 0.5 + 0.5 * d / top;
                paint(heat, left + x, mapTop + y, !(u >= 0.0 && u <= 1.0) ? kSignedClipped : coolWarm(u));
            }
        drawGlyphText(heat, left, mapTop + a.height + kTitleTop, cell, a.channelNames[std::size_t(c)],
                      {0.0f, 0.0f, 0.0f, 1.0f});
    }
    drawBar(heat, mapTop + a.height + namesRows + kGap, ticks, coolWarm);
    return heat;
}

}  // namespace vri
