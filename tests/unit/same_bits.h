#pragma once
// Whether two images hold the same bits, pixel for pixel: the tests' check of "bitwise the same image".
#include <cstring>

#include "libvri/core/image.h"

namespace vri::test {

inline bool sameBits(const Image& a, const Image& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

}  // namespace vri::test
