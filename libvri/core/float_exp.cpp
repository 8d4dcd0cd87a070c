#include "libvri/core/float_exp.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "libvri/core/exp_kernel.h"

namespace vri {

namespace {

// exp_kernel.h's operations on one float.
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

}  // namespace

float expFloat(float x) { return exp_kernel::exp(ScalarExpOps{}, x); }
float expm1Float(float x) { return exp_kernel::expm1(ScalarExpOps{}, x); }

}  // namespace vri
