#pragma once
// Numbers drawn into an image: the labels of a heat map's colour bar, so that a PNG states its own scale
// without a font library. Glyphs of 3 x 5 cells for the characters a number prints with ("%g": digits,
// '.', '-', '+', 'e'), each cell `scale` x `scale` pixels, one empty cell column between glyphs.
#include <array>
#include <string_view>

#include "libvri/core/image.h"

namespace vri {

inline constexpr int kGlyphColumns = 3, kGlyphRows = 5;

// The width in pixels of `text` drawn at `scale` (no trailing gap): 4 * scale per character, less one
// cell. Throws vri::Error for a character without a glyph.
int numberTextWidth(std::string_view text, int scale);

// Draws `text` with its top left corner at (x, y) in `colour` (linear RGBA), cells outside the image
// left out. Throws vri::Error for a character without a glyph.
void drawNumberText(Image& image, int x, int y, int scale, std::string_view text, const std::array<float, 4>& colour);

}  // namespace vri
