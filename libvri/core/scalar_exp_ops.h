#pragma once
// exp_kernel.h's operations on one float: the scalar float path's exp and expm1 (float_exp.cpp).
#include <algorithm>
#include <bit>
#include <cstdint>

namespace vri {

struct ScalarExpOps {
    using Scalar = float;
    static float set(float c) { return c; }
    static float select(bool c, float a, float b) { return c ? a : b; }
    static std::int32_t toInt(float k) { return static_cast<std::int32_t>(k); }
    static float pow2(std::int32_t k) { return std::bit_cast<float>(static_cast<std::uint32_t>(k + 127) << 23); }
    static std::int32_t halve(std::int32_t k) { return k >> 1; }  // arithmetic in C++20
    static std::int32_t clampInt(std::int32_t k, int lo, int hi) { return std::clamp(k, lo, hi); }
    static float clamp(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }
    static bool intGreater(std::int32_t a, int b) { return a > b; }
    static bool isNaN(float x) { return x != x; }
};

}  // namespace vri
