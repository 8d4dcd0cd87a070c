#pragma once
// PNG previews through libpng itself (not OpenImageIO, whose plug-ins cost every process most of a second
// to load). Private to image_io.cpp.
#include <cstdint>
#include <string>
#include <vector>

namespace vri::detail {

// An 8-bit RGB PNG in memory, rows top to bottom, marked sRGB (its sRGB chunk): the caller writes it
// with its checked writes. `rgb` holds width * height * 3 bytes.
std::string encodePngRgb8(int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace vri::detail
