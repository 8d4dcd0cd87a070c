#pragma once
// Text drawn into an image: a heat map's title line and the labels of its colour bar, so that a PNG states
// what it shows and its own scale without a font library. Glyphs of 3 x 5 cells: digits, upper-case letters
// (a lower-case letter is drawn as its capital), blank and the marks a title or a number prints with
// (. - + : | ( ) / _ , = < > % * ^); any other character, a multi-byte UTF-8 one included, is drawn as
// one '?'. Each cell is `scale` x `scale`
// pixels, one empty cell column between glyphs.
#include <array>
#include <string_view>

#include "libvri/core/image.h"

namespace vri {

inline constexpr int kGlyphColumns = 3, kGlyphRows = 5;

// The width in pixels of `text` (UTF-8) drawn at `scale` (no trailing gap): 4 * scale per character, less one
// cell.
int glyphTextWidth(std::string_view text, int scale);

// Draws `text` with its top left corner at (x, y) in `colour` (linear RGBA), cells outside the image left out.
void drawGlyphText(Image& image, int x, int y, int scale, std::string_view text, const std::array<float, 4>& colour);

}  // namespace vri
