// A 3 x 5 bitmap font for numbers.
#include "libvri/core/number_glyphs.h"

#include <cstdint>
#include <string>

#include "libvri/util/error.h"

namespace vri {

namespace {

// Each glyph as 5 rows, top first, of 3 bits, the leftmost cell the highest bit.
struct Glyph {
    char character;
    std::array<std::uint8_t, kGlyphRows> rows;
};
constexpr std::array<Glyph, 14> kGlyphs{{
    {'0', {0b111, 0b101, 0b101, 0b101, 0b111}},
    {'1', {0b010, 0b110, 0b010, 0b010, 0b111}},
    {'2', {0b111, 0b001, 0b111, 0b100, 0b111}},
    {'3', {0b111, 0b001, 0b011, 0b001, 0b111}},
    {'4', {0b101, 0b101, 0b111, 0b001, 0b001}},
    {'5', {0b111, 0b100, 0b111, 0b001, 0b111}},
    {'6', {0b111, 0b100, 0b111, 0b101, 0b111}},
    {'7', {0b111, 0b001, 0b010, 0b010, 0b010}},
    {'8', {0b111, 0b101, 0b111, 0b101, 0b111}},
    {'9', {0b111, 0b101, 0b111, 0b001, 0b111}},
    {'.', {0b000, 0b000, 0b000, 0b000, 0b010}},
    {'-', {0b000, 0b000, 0b111, 0b000, 0b000}},
    {'+', {0b000, 0b010, 0b111, 0b010, 0b000}},
    {'e', {0b000, 0b111, 0b111, 0b100, 0b111}},
}};

const Glyph& glyphOf(char c) {
    for (const Glyph& g : kGlyphs)
        if (g.character == c) return g;
    throw Error(std::string("number text: no glyph for '") + c + "'");
}

}  // namespace

int numberTextWidth(std::string_view text, int scale) {
    for (char c : text) glyphOf(c);
    return text.empty() ? 0 : (int(text.size()) * (kGlyphColumns + 1) - 1) * scale;
}

void drawNumberText(Image& image, int x, int y, int scale, std::string_view text, const std::array<float, 4>& colour) {
    for (char c : text) {
        const Glyph& g = glyphOf(c);
        for (int row = 0; row < kGlyphRows; ++row)
            for (int column = 0; column < kGlyphColumns; ++column) {
                if (!(g.rows[row] >> (kGlyphColumns - 1 - column) & 1)) continue;
                for (int dy = 0; dy < scale; ++dy)
                    for (int dx = 0; dx < scale; ++dx) {
                        const int px = x + column * scale + dx, py = y + row * scale + dy;
                        if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
                        for (int k = 0; k < 4 && k < image.channels; ++k) image.at(px, py, k) = colour[k];
                    }
            }
        x += (kGlyphColumns + 1) * scale;
    }
}

}  // namespace vri
