// A 3 x 5 bitmap font.
#include "libvri/core/text_glyphs.h"

#include <cstdint>
#include <string>

namespace vri {

namespace {

// Each glyph as 5 rows, top first, of 3 bits, the leftmost cell the highest bit.
struct Glyph {
    char character;
    std::array<std::uint8_t, kGlyphRows> rows;
};
constexpr std::array<Glyph, 54> kGlyphs{{
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
    {'A', {0b010, 0b101, 0b111, 0b101, 0b101}},
    {'B', {0b110, 0b101, 0b110, 0b101, 0b110}},
    {'C', {0b011, 0b100, 0b100, 0b100, 0b011}},
    {'D', {0b110, 0b101, 0b101, 0b101, 0b110}},
    {'E', {0b111, 0b100, 0b110, 0b100, 0b111}},
    {'F', {0b111, 0b100, 0b110, 0b100, 0b100}},
    {'G', {0b011, 0b100, 0b101, 0b101, 0b011}},
    {'H', {0b101, 0b101, 0b111, 0b101, 0b101}},
    {'I', {0b111, 0b010, 0b010, 0b010, 0b111}},
    {'J', {0b001, 0b001, 0b001, 0b101, 0b010}},
    {'K', {0b101, 0b101, 0b110, 0b101, 0b101}},
    {'L', {0b100, 0b100, 0b100, 0b100, 0b111}},
    {'M', {0b101, 0b111, 0b111, 0b101, 0b101}},
    {'N', {0b110, 0b101, 0b101, 0b101, 0b101}},
    {'O', {0b010, 0b101, 0b101, 0b101, 0b010}},
    {'P', {0b110, 0b101, 0b110, 0b100, 0b100}},
    {'Q', {0b010, 0b101, 0b101, 0b110, 0b011}},
    {'R', {0b110, 0b101, 0b110, 0b101, 0b101}},
    {'S', {0b011, 0b100, 0b010, 0b001, 0b110}},
    {'T', {0b111, 0b010, 0b010, 0b010, 0b010}},
    {'U', {0b101, 0b101, 0b101, 0b101, 0b111}},
    {'V', {0b101, 0b101, 0b101, 0b101, 0b010}},
    {'W', {0b101, 0b101, 0b111, 0b111, 0b101}},
    {'X', {0b101, 0b101, 0b010, 0b101, 0b101}},
    {'Y', {0b101, 0b101, 0b010, 0b010, 0b010}},
    {'Z', {0b111, 0b001, 0b010, 0b100, 0b111}},
    {' ', {0b000, 0b000, 0b000, 0b000, 0b000}},
    {'.', {0b000, 0b000, 0b000, 0b000, 0b010}},
    {'-', {0b000, 0b000, 0b111, 0b000, 0b000}},
    {'+', {0b000, 0b010, 0b111, 0b010, 0b000}},
    {':', {0b000, 0b010, 0b000, 0b010, 0b000}},
    {'|', {0b010, 0b010, 0b010, 0b010, 0b010}},
    {'(', {0b001, 0b010, 0b010, 0b010, 0b001}},
    {')', {0b100, 0b010, 0b010, 0b010, 0b100}},
    {'/', {0b001, 0b001, 0b010, 0b100, 0b100}},
    {'_', {0b000, 0b000, 0b000, 0b000, 0b111}},
    {',', {0b000, 0b000, 0b000, 0b010, 0b100}},
    {'=', {0b000, 0b111, 0b000, 0b111, 0b000}},
    {'<', {0b001, 0b010, 0b100, 0b010, 0b001}},
    {'>', {0b100, 0b010, 0b001, 0b010, 0b100}},
    {'%', {0b101, 0b001, 0b010, 0b100, 0b101}},
    {'*', {0b000, 0b101, 0b010, 0b101, 0b000}},
    {'^', {0b010, 0b101, 0b000, 0b000, 0b000}},
    {'?', {0b111, 0b001, 0b010, 0b000, 0b010}},
}};

// A character's glyph: a lower-case letter's capital's, '?' for one the font lacks.
const Glyph& glyphOf(char c) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    for (const Glyph& g : kGlyphs)
        if (g.character == c) return g;
    return kGlyphs.back();
}

// The characters of UTF-8 text: a multi-byte character (its continuation bytes 10xxxxxx skipped) is one '?'.
std::string glyphCharacters(std::string_view text) {
    std::string characters;
    for (const char c : text)
        if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) characters += static_cast<unsigned char>(c) < 0x80 ? c : '?';
    return characters;
}

}  // namespace

int glyphTextWidth(std::string_view text, int scale) {
    const std::size_t n = glyphCharacters(text).size();
    return n == 0 ? 0 : (int(n) * (kGlyphColumns + 1) - 1) * scale;
}

void drawGlyphText(Image& image, int x, int y, int scale, std::string_view text, const std::array<float, 4>& colour) {
    for (char c : glyphCharacters(text)) {
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
