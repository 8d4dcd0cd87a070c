// The packet engine (simd_march.h). Highway compiles the part between HWY_BEFORE_NAMESPACE and
// HWY_AFTER_NAMESPACE once per target (foreach_target.h re-includes this file); the rest, once.
#include "libvri/core/simd_march.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "libvri/core/simd_march.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "libvri/core/fixed_step_ray.h"
#include "libvri/core/jitter.h"
#include "libvri/core/preintegration_table.h"

HWY_BEFORE_NAMESPACE();
#include "libvri/core/exp_kernel.h"  // once per target, see there

namespace vri {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

// ConvertTo(di, x) for lanes known to hold a value within int32's range (or to be discarded): the
// truncating conversion alone. On x86 Highway's ConvertTo also fixes up lanes that overflow, four more
// operations a conversion; the march converts five times a sample, and AVX2's eight lanes pay for them
// twice as often as AVX-512's sixteen. In range the two agree bit for bit. (AVX-512's zero-masked form
// with every lane selected is the same instruction; GCC 12 warns of an uninitialised value in the
// unmasked one's header.)
HWY_INLINE VI truncateInRange(VF x) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    return VI{_mm512_maskz_cvttps_epi32(__mmask16(0xFFFF), x.raw)};
#elif HWY_ARCH_X86 && HWY_TARGET == HWY_AVX2
    return VI{_mm256_cvttps_epi32(x.raw)};
#elif HWY_ARCH_X86 && (HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_SSSE3)
    return VI{_mm_cvttps_epi32(x.raw)};
#else
    return hn::ConvertTo(DI(), x);
#endif
}

// exp_kernel.h's operations, lane by lane.
struct VectorOps {
    using Scalar = float;
    DF df;
    DI di;
    VF set(float c) const { return hn::Set(df, c); }
    VF select(MF m, VF a, VF b) const { return hn::IfThenElse(m, a, b); }
    VI toInt(VF k) const { return truncateInRange(k); }  // k is within [-150, 129] (exp_kernel.h)
    VF pow2(VI k) const { return hn::BitCast(df, hn::ShiftLeft<23>(hn::Add(k, hn::Set(di, 127)))); }
    VI halve(VI k) const { return hn::ShiftRight<1>(k); }
    VI clampInt(VI k, int lo, int hi) const { return hn::Min(hn::Max(k, hn::Set(di, lo)), hn::Set(di, hi)); }
    VF clamp(VF x, VF lo, VF hi) const { return hn::Min(hi, hn::Max(lo, x)); }
    MF intGreater(VI a, int b) const { return hn::RebindMask(df, hn::Gt(a, hn::Set(di, b))); }
    MF isNaN(VF x) const { return hn::IsNaN(x); }
};

HWY_INLINE VF lerp(VF a, VF b, VF t) { return hn::Add(a, hn::Mul(t, hn::Sub(b, a))); }

// Voxels o and o + 1 of each lane (the x neighbours: the x stride is 1).
struct VoxelPair {
    VF first, second;
};

// The pairs at the lanes' offsets o. `nearEnd`: whether voxel o + 3 may lie past the volume's end (a
// gathered word of 8-bit voxels would then read past it).
template <class T>
VoxelPair gatherPair(const PacketScene& sc, VI o, bool nearEnd);

template <>
HWY_INLINE VoxelPair gatherPair<std::uint8_t>(const PacketScene& sc, VI o, bool nearEnd) {
    const DF df;
    const DI di;
    const DU du;
    const auto* words = reinterpret_cast<const std::int32_t*>(sc.voxels);
    // One 32-bit word holds both bytes. Near the end the volume's last word starts 4 bytes before it:
    // a lane past that reads it and shifts its bytes down.
    const VI start = nearEnd ? hn::Min(o, hn::Set(di, sc.voxelBytes - 4)) : o;
    auto bytes = hn::BitCast(du, hn::GatherOffset(di, words, start));
    if (nearEnd) bytes = bytes >> hn::BitCast(du, hn::ShiftLeft<3>(hn::Sub(o, start)));
    const auto mask = hn::Set(du, 0xFFu);
    return {hn::ConvertTo(df, hn::BitCast(di, hn::And(bytes, mask))),
            hn::ConvertTo(df, hn::BitCast(di, hn::And(hn::ShiftRight<8>(bytes), mask)))};
}

template <>
HWY_INLINE VoxelPair gatherPair<std::uint16_t>(const PacketScene& sc, VI o, bool) {
    const DF df;
    const DI di;
    const DU du;
    // Voxel o + 1 exists (o is never the last voxel of a row), so the word at 2 o lies inside the volume.
    const auto word =
        hn::BitCast(du, hn::GatherOffset(di, reinterpret_cast<const std::int32_t*>(sc.voxels), hn::ShiftLeft<1>(o)));
    return {hn::ConvertTo(df, hn::BitCast(di, hn::And(word, hn::Set(du, 0xFFFFu)))),
            hn::ConvertTo(df, hn::BitCast(di, hn::ShiftRight<16>(word)))};
}

template <>
HWY_INLINE VoxelPair gatherPair<float>(const PacketScene& sc, VI o, bool) {
    const DF df;
    const DI di;
    const float* data = reinterpret_cast<const float*>(sc.voxels);
    return {hn::GatherIndex(df, data, o), hn::GatherIndex(df, data, hn::Add(o, hn::Set(di, 1)))};
}

// GridSampler<T, float>::operator() in two halves: where each lane's trilinear stencil lies, then
// its value. Lanes outside `valid` address voxel 0.
struct Stencil {
    VI base;     // the stencil's lowest voxel
    VF w[3];     // the weights along x, y, z
    VF x[3];     // the continuous voxel index, before clamping
    VI cell[3];  // the stencil brick holding `base` along each axis, and its index in the grid (occupancy_grid.h)
    VI brick;
};

HWY_INLINE Stencil locate(const PacketScene& sc, const VF (&u)[3], MF valid) {
    const DF df;
    const DI di;
    const GridSamplerLayout<float>& g = sc.layout;
    Stencil st{hn::Zero(di), {}, {}, {}, hn::Zero(di)};
    for (int a = 0; a < 3; ++a) {
        const VF x = st.x[a] = hn::Sub(hn::Mul(u[a], hn::Set(df, g.scale[a])), hn::Set(df, g.offset[a]));
        const VF maxCoord = hn::Set(df, g.maxCoord[a]);
        // GridSampler's clamp, x < 0 ? 0 : maxCoord < x ? maxCoord : x, as a max and a min: the same for
        // every x but NaN (a target's max may turn -0 into +0, which no weight's product can show). c lies
        // in [0, maxCoord] on a valid lane (its ray's positions are finite); the others are zeroed.
        const VF c = hn::Min(maxCoord, hn::Max(hn::Zero(df), x));
        const VI i =
            hn::IfThenElseZero(hn::RebindMask(di, valid), hn::Min(truncateInRange(c), hn::Set(di, g.maxBase[a])));
        st.w[a] = hn::Sub(c, hn::ConvertTo(df, i));
        st.base = hn::Add(st.base, hn::Mul(i, hn::Set(di, static_cast<std::int32_t>(g.stride[a]))));
        st.cell[a] = hn::ShiftRight<StencilBricks::kShift>(i);
        st.brick = hn::Add(st.brick, hn::Mul(st.cell[a], hn::Set(di, sc.brickStride[a])));
    }
    return st;
}

#if HWY_TARGET == HWY_AVX2
// gatherStencil<std::uint8_t>'s pairs, lane by lane with scalar loads (voxel_loads.h). A pair's two bytes
// lie in the volume, so no guard is needed at its end.
HWY_INLINE void loadStencilBytes(const PacketScene& sc, VI base, VoxelPair (&p)[4]) {
    const DF df;
    const DI di;
    const DU du;
    const GridSamplerLayout<float>& g = sc.layout;
    HWY_ALIGN std::int32_t at[PacketScene::kMaxLanes];
    hn::Store(base, di, at);
    const std::ptrdiff_t offset[4] = {0, g.stride[1], g.stride[2], g.stride[1] + g.stride[2]};
    HWY_ALIGN std::uint32_t words[4][PacketScene::kMaxLanes];
    const auto* voxels = reinterpret_cast<const unsigned char*>(sc.voxels);
    for (std::size_t lane = 0; lane < hn::Lanes(di); ++lane)
        for (int q = 0; q < 4; ++q) {
            std::uint16_t pair;
            std::memcpy(&pair, voxels + at[lane] + offset[q], sizeof pair);
            words[q][lane] = pair;
        }
    const auto mask = hn::Set(du, 0xFFu);
    for (int q = 0; q < 4; ++q) {
        const auto word = hn::Load(du, words[q]);
        p[q] = {hn::ConvertTo(df, hn::BitCast(di, hn::And(word, mask))),
                hn::ConvertTo(df, hn::BitCast(di, hn::ShiftRight<8>(word)))};
    }
}
#endif

// The distances of the lanes' stencil bricks (PacketScene::emptyDistance, a byte each at `brick`).
HWY_INLINE VI brickDistances(const PacketScene& sc, VI brick) {
    const DI di;
#if HWY_TARGET == HWY_AVX2
    if (sc.voxelLoads == VoxelLoads::Scalar) {
        HWY_ALIGN std::int32_t at[PacketScene::kMaxLanes], distance[PacketScene::kMaxLanes];
        hn::Store(brick, di, at);
        for (std::size_t lane = 0; lane < hn::Lanes(di); ++lane)
            distance[lane] = sc.emptyDistance[at[lane]];
        return hn::Load(di, distance);
    }
#endif
    // The word at each brick's byte; its low byte is the distance.
    const VI word = hn::GatherOffset(di, reinterpret_cast<const std::int32_t*>(sc.emptyDistance), brick);
    return hn::And(word, hn::Set(di, 0xFF));
}

// The four x pairs of the lanes' stencils at `base`: (y, z) = (0, 0), (1, 0), (0, 1), (1, 1).
template <class T>
HWY_INLINE void gatherStencil(const PacketScene& sc, VI base, VoxelPair (&p)[4]) {
#if HWY_TARGET == HWY_AVX2
    if constexpr (std::is_same_v<T, std::uint8_t>)
        if (sc.voxelLoads == VoxelLoads::Scalar) return loadStencilBytes(sc, base, p);
#endif
    const DI di;
    const GridSamplerLayout<float>& g = sc.layout;
    const VI sy = hn::Set(di, static_cast<std::int32_t>(g.stride[1]));
    const VI sz = hn::Set(di, static_cast<std::int32_t>(g.stride[2]));
    // The stencil's last voxel, base + sy + sz + 1, lies in the volume, so the words of its first three
    // pairs end within it where the strides along y and z are 2 or more (not a single layer).
    const bool thin = g.stride[1] < 2 || g.stride[2] < 2;
    p[0] = gatherPair<T>(sc, base, thin);
    p[1] = gatherPair<T>(sc, hn::Add(base, sy), thin);
    p[2] = gatherPair<T>(sc, hn::Add(base, sz), thin);
    p[3] = gatherPair<T>(sc, hn::Add(hn::Add(base, sz), sy), true);
}

template <class T>
HWY_INLINE VF interpolate(const PacketScene& sc, const Stencil& st) {
    const DF df;
    const GridSamplerLayout<float>& g = sc.layout;
    VoxelPair p[4];
    gatherStencil<T>(sc, st.base, p);
    const VoxelPair &p00 = p[0], &p10 = p[1], &p01 = p[2], &p11 = p[3];
    const VF c00 = lerp(p00.first, p00.second, st.w[0]);
    const VF c10 = lerp(p10.first, p10.second, st.w[0]);
    const VF c01 = lerp(p01.first, p01.second, st.w[0]);
    const VF c11 = lerp(p11.first, p11.second, st.w[0]);
    const VF c0 = lerp(c00, c10, st.w[1]);
    const VF c1 = lerp(c01, c11, st.w[1]);
    return hn::Mul(hn::Sub(lerp(c0, c1, st.w[2]), hn::Set(df, g.lo)), hn::Set(df, g.invRange));
}

// How many samples after the current one certainly keep their stencil in bricks known to be empty:
// the lanes' bricks lie `distance` bricks from the nearest brick ahead of them that is not empty (in
// their ray's octant), so every brick from theirs to less than that far ahead along each axis is
// empty (bricks outside the grid do not count: a stencil there is clamped into the grid, onto a brick
// of the cube). The stencils only move ahead: a sample's position along an axis is entry + (tStart +
// k tIncr) du, each operation rounding monotonically, so it never decreases with k where du > 0 and
// never increases where du < 0, and so neither do the clamp and floor of locate(). Along each axis, the
// distance to the cube's face the ray heads for, less `margin` voxels (far more than the rounding of
// sample positions and of this estimate, even across the whole volume), in samples
// (`samplesPerVoxel`, +inf along an axis the ray does not move on), minus one for the rounding of
// this estimate. Skipping them changes nothing.
HWY_INLINE VI samplesInEmptyCube(const Stencil& st, VI distance, const VF (&du)[3], const VF (&samplesPerVoxel)[3],
                                 float margin) {
    const DF df;
    const DI di;
    VF samples = hn::Set(df, 1e9f);
    for (int a = 0; a < 3; ++a) {
        const VF lo = hn::ConvertTo(
            df, hn::ShiftLeft<StencilBricks::kShift>(hn::Add(hn::Sub(st.cell[a], distance), hn::Set(di, 1))));
        const VF hi = hn::ConvertTo(df, hn::ShiftLeft<StencilBricks::kShift>(hn::Add(st.cell[a], distance)));
        const VF room = hn::IfThenElse(hn::Gt(du[a], hn::Zero(df)), hn::Sub(hi, st.x[a]), hn::Sub(st.x[a], lo));
        const VF along = hn::Mul(hn::Sub(room, hn::Set(df, margin)), samplesPerVoxel[a]);
        samples = hn::IfThenElse(hn::Eq(du[a], hn::Zero(df)), samples, hn::Min(samples, along));
    }
    return truncateInRange(hn::Max(hn::Sub(samples, hn::Set(df, 1.f)), hn::Zero(df)));  // in [0, 1e9)
}

// TransferFunction::operator()<float>: the bracket p_i <= s < p_i+1 is the number of inner points
// p_1 .. p_n-2 at or below s, the same bracket the scalar search finds. Its constants come from
// registers when every segment fits one vector or two (a lane permutation each, and a select between
// the two), else from memory (a gather each). On AVX2's 8 lanes a gather costs far more than the
// permutations: Bonsai's 8 segments in memory made AVX2 packets twice as slow, per lane, as AVX-512's
// 16, which held them in one register.
class VectorTransferFunction {
public:
    explicit VectorTransferFunction(const PacketScene& sc) : sc_(sc) {
        const DF df;
        const std::size_t n = hn::Lanes(df);
        tables_ = sc.segments <= n ? 1 : sc.segments <= 2 * n && sc.segmentStart.size() >= 2 * n ? 2 : 0;
        for (int half = 0; half < 2; ++half) {
            start_[half] = width_[half] = hn::Zero(df);
            for (int c = 0; c < 4; ++c)
                value_[half][c] = slope_[half][c] = hn::Zero(df);
        }
        for (int half = 0; half < tables_; ++half) {
            const std::size_t at = half * n;
            start_[half] = hn::LoadU(df, sc.segmentStart.data() + at);
            width_[half] = hn::LoadU(df, sc.segmentWidth.data() + at);
            for (int c = 0; c < 4; ++c) {
                value_[half][c] = hn::LoadU(df, sc.value[c].data() + at);
                slope_[half][c] = hn::LoadU(df, sc.slope[c].data() + at);
            }
        }
    }

    // r, g, b, tau of the lanes' s; only those of `lanes` need be right.
    HWY_INLINE void operator()(VF s, MF lanes, VF (&out)[4]) const {
        const DF df;
        const DI di;
        // Four inner points a turn (NaN pads the last four: s >= NaN is false), each a compare and a
        // subtraction: a loop over single points spent more on the loop than on the compares.
        const std::vector<float>& inner = sc_.innerS;
        // A true compare is -1 as an integer: subtracting it counts the point.
        VI segment = hn::Zero(di);
        const auto count = [&](float p) {
            segment = hn::Sub(segment, hn::VecFromMask(di, hn::RebindMask(di, hn::Ge(s, hn::Set(df, p)))));
        };
        for (std::size_t j = 0; j < inner.size(); j += 4) {
            count(inner[j]);
            count(inner[j + 1]);
            count(inner[j + 2]);
            count(inner[j + 3]);
        }
        const MF above = hn::Ge(s, hn::Set(df, sc_.pointS.front()));
        const MF below = hn::Lt(s, hn::Set(df, sc_.pointS.back()));
        if (tables_ == 1) {
            const auto idx = hn::IndicesFromVec(df, segment);
            const auto lookup = [&](const VF(&table)[2]) { return hn::TableLookupLanes(table[0], idx); };
            evaluate(s, lookup, out);
        } else if (tables_ == 2) {
            // Segments n .. 2n - 1 lie in the second vector, at their index less n.
            const VI lanes = hn::Set(di, static_cast<std::int32_t>(hn::Lanes(df)));
            const auto second = hn::Gt(segment, hn::Sub(lanes, hn::Set(di, 1)));
            const auto idx = hn::IndicesFromVec(df, hn::IfThenElse(second, hn::Sub(segment, lanes), segment));
            const MF inSecond = hn::RebindMask(df, second);
            const auto lookup = [&](const VF(&table)[2]) {
                return hn::IfThenElse(inSecond, hn::TableLookupLanes(table[1], idx), hn::TableLookupLanes(table[0], idx));
            };
            evaluate(s, lookup, out);
        } else {
            const auto gather = [&](const std::vector<float>& table) { return hn::GatherIndex(df, table.data(), segment); };
            const VF w = hn::Div(hn::Sub(s, gather(sc_.segmentStart)), gather(sc_.segmentWidth));
            for (int c = 0; c < 4; ++c)
                out[c] = hn::Add(gather(sc_.value[c]), hn::Mul(w, gather(sc_.slope[c])));
        }
        // Below the first point (or NaN): the first point's value; at or past the last: the last's. Rare
        // enough (at s = 1 on 8-bit data whose last point is at 1) that they are picked only when needed.
        if (!hn::AllFalse(df, hn::AndNot(hn::And(above, below), lanes)))
            for (int c = 0; c < 4; ++c)
                out[c] = hn::IfThenElse(above, hn::IfThenElse(below, out[c], hn::Set(df, sc_.last[c])),
                                        hn::Set(df, sc_.first[c]));
    }

private:
    // The lerp within the lanes' segments, its constants from `lookup` (one or two vectors per constant).
    template <class Lookup>
    HWY_INLINE void evaluate(VF s, const Lookup& lookup, VF (&out)[4]) const {
        const VF w = hn::Div(hn::Sub(s, lookup(start_)), lookup(width_));
        for (int c = 0; c < 4; ++c) {
            const VF value[2] = {value_[0][c], value_[1][c]}, slope[2] = {slope_[0][c], slope_[1][c]};
            out[c] = hn::Add(lookup(value), hn::Mul(w, lookup(slope)));
        }
    }

    const PacketScene& sc_;
    int tables_ = 0;  // vectors per constant in registers: 1 or 2; 0: the constants are gathered from memory
    VF start_[2], width_[2], value_[2][4], slope_[2][4];
};

// The largest exponent -tau dx of a packet's steps: within exp_kernel::kNearZero of 0, within
// kNormalRange, or any.
enum class StepDepth { NearZero, NormalRange, Any };

// The depth class of exponents down to -deepest (the lanes' largest), with a margin for the rounding of
// their factors and of the product.
HWY_INLINE StepDepth stepDepthOf(VF deepest) {
    const DF df;
    if (hn::AllTrue(df, hn::Le(deepest, hn::Set(df, 0.97f * float(exp_kernel::kNearZero))))) return StepDepth::NearZero;
    if (hn::AllTrue(df, hn::Le(deepest, hn::Set(df, 0.97f * float(exp_kernel::kNormalRange)))))
        return StepDepth::NormalRange;
    return StepDepth::Any;
}

// A step's attenuation exp(x) in the shortest form of exp_kernel.h that `depth` allows: exp()'s bits.
HWY_INLINE VF stepAttenuation(const VectorOps& ops, StepDepth depth, VF x) {
    if (depth == StepDepth::NearZero) return exp_kernel::expNearZero(ops, x);
    if (depth == StepDepth::NormalRange) return exp_kernel::expInNormalRange(ops, x);
    return exp_kernel::exp(ops, x);
}

// stepAttenuation, and for composite expm1(x) in its shortest form too.
template <Integrator Method>
HWY_INLINE void stepExponentials(const VectorOps& ops, StepDepth depth, VF x, VF& exp, VF& expm1) {
    exp = stepAttenuation(ops, depth, x);
    if constexpr (Method != Integrator::Riemann)
        expm1 = depth == StepDepth::NearZero      ? exp_kernel::expm1NearZero(ops, x)
                : depth == StepDepth::NormalRange ? exp_kernel::expm1InNormalRange(ops, x)
                                                  : exp_kernel::expm1(ops, x);
}

constexpr std::size_t kMaxLanes = PacketScene::kMaxLanes;
static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxLanes);

// The order in which a tile's pixels enter packets: blocks of neighbouring pixels as near square as
// the lane count allows (4x4 for 16 lanes, 4x2 for 8, 2x2 for 4), block after block along the tile's
// rows. A block's rays start close together and stay close, so its lanes cross the same bricks (their
// jumps and their ends come together) and its gathers share cache lines, more than a row of pixels'
// would. The order changes no pixel's value: each lane marches its own ray.
class PacketOrder {
public:
    PacketOrder(int width, int height, std::size_t lanes)
        : width_(width), height_(height), blockW_(lanes >= 8 ? 4 : lanes >= 4 ? 2 : static_cast<int>(lanes)),
          blockH_(static_cast<int>(lanes) / blockW_) {}

    bool done() const { return y_ >= height_; }

    // The next pixel, as x + width * y within the tile; false when none is left.
    bool next(int& pixel) {
        while (!done()) {
            const int x = x_ + i_ % blockW_, y = y_ + i_ / blockW_;
            if (++i_ == blockW_ * blockH_) {
                i_ = 0;
                x_ += blockW_;
                if (x_ >= width_) {
                    x_ = 0;
                    y_ += blockH_;
                }
            }
            if (x < width_ && y < height_) {
                pixel = x + width_ * y;
                return true;
            }
        }
        return false;
    }

private:
    int width_, height_, blockW_, blockH_;
    int x_ = 0, y_ = 0, i_ = 0;  // the block's corner, and the next pixel's place in it
};

// A pixel's ray as the packets march it: pixelRay<float>() and FixedStepSamples<float> of it.
struct PixelSamples {
    int pixel;
    bool hit;  // the ray meets the box
    double worldLength;
    SampleSchedule<float> schedule;
    glm::vec3 entry, du;
    float dx;
};

// The rays of the next pixels in PacketOrder, a vector of pixels at a time: pixelRay() (Camera::
// direction(), clipRay(), Box::toTexture()) in double, then placeSamples() and FixedStepSamples in
// float, operation for operation (no fused multiply-add: the build turns contraction off), so every
// ray has the bits of the scalar path's; the count of a fixed step is countBelowEnd()'s. A pixel whose
// direction has a zero or non-finite component takes pixelRay() itself (clipRay()'s cases for those).
class RayBatch {
public:
    explicit RayBatch(const PacketScene& sc) : sc_(sc), basis_(sc.camera.basis()) {}

    // The next pixel's ray; false when the tile has no pixel left.
    bool next(PacketOrder& order, int x0, int y0, int width, PixelSamples& ray) {
        if (next_ == size_) fill(order, x0, y0, width);
        if (next_ == size_) return false;
        const std::size_t i = next_++;
        ray.pixel = pixel_[i];
        const int px = x0 + ray.pixel % width, py = y0 + ray.pixel / width;
        // The scalar path's jitter (cpu_renderer.cpp): the hashed fraction, exact in float, moves the
        // first sample after the placement, and the count follows from it.
        const std::optional<float> jitter =
            sc_.options.jitter ? std::optional<float>(static_cast<float>(jitterFraction(px, py, sc_.options.seed)))
                               : std::nullopt;
        if (scalar_[i] != 0.0) {
            const auto clipped = pixelRay<float>(sc_.camera, sc_.box, px, py);
            ray.hit = clipped.has_value();
            if (!clipped) return true;
            const FixedStepSamples<float> samples(*clipped, sc_.options, sc_.eyeU, sc_.dims, jitter);
            ray.worldLength = clipped->worldLength;
            ray.schedule = samples.schedule;
            ray.entry = samples.entry;
            ray.du = samples.du;
            ray.dx = samples.dx;
            return true;
        }
        ray.hit = hit_[i] != 0.0;
        ray.worldLength = length_[i];
        SampleSchedule<float>& s = ray.schedule;
        s = {tStart_[i], tIncr_[i], tEnd_[i], 0};
        if (!ray.hit || !(s.tEnd > 0.f) || !(samples_[i] > 0.f) || !std::isfinite(samples_[i])) {
            s = {0.f, 0.f, s.tEnd, 0};
            return true;
        }
        const Placement placement = sc_.options.placement;
        s.count = placement == Placement::EntryExitAlign || placement == Placement::EntryExitAlignCorner
                      ? static_cast<std::int64_t>(samples_[i])
                      : countBelowEnd(s);
        if (jitter) jitterSchedule(s, *jitter);
        ray.entry = glm::vec3(entryF_[0][i], entryF_[1][i], entryF_[2][i]);
        ray.du = glm::vec3(du_[0][i], du_[1][i], du_[2][i]);
        ray.dx = s.count > 0 ? s.tIncr * static_cast<float>(ray.worldLength / static_cast<double>(s.tEnd)) : 0.f;
        return true;
    }

private:
    using DD = hn::ScalableTag<double>;
    using VD = hn::Vec<DD>;

    void fill(PacketOrder& order, int x0, int y0, int width) {
        size_ = next_ = 0;
        HWY_ALIGN double px[kBatch] = {}, py[kBatch] = {};  // a partial last vector reads zeros
        while (size_ < kBatch && order.next(pixel_[size_])) {
            px[size_] = x0 + pixel_[size_] % width;
            py[size_] = y0 + pixel_[size_] / width;
            ++size_;
        }
        const DD dd;
        const std::size_t n = hn::Lanes(dd);
        const CameraSpec& spec = sc_.camera.spec();
        const VD zero = hn::Zero(dd), one = hn::Set(dd, 1.0), two = hn::Set(dd, 2.0), half = hn::Set(dd, 0.5);
        for (std::size_t j = 0; j < size_; j += n) {
            // Camera::direction().
            const VD fx = hn::Add(hn::Set(dd, basis_.centre.x),
                                  hn::Div(hn::Sub(hn::Add(hn::Load(dd, px + j), half), hn::Set(dd, 0.5 * spec.width)),
                                          hn::Set(dd, spec.zoom)));
            const VD fy = hn::Add(hn::Set(dd, basis_.centre.y),
                                  hn::Div(hn::Sub(hn::Add(hn::Load(dd, py + j), half), hn::Set(dd, 0.5 * spec.height)),
                                          hn::Set(dd, spec.zoom)));
            const VD x =
                hn::Mul(hn::Sub(hn::Div(hn::Mul(two, fx), hn::Set(dd, spec.width)), one), hn::Set(dd, basis_.tanHalfX));
            const VD y = hn::Mul(hn::Sub(one, hn::Div(hn::Mul(two, fy), hn::Set(dd, spec.height))),
                                 hn::Set(dd, basis_.tanHalfY));
            VD v[3];
            for (int a = 0; a < 3; ++a)
                v[a] = hn::Add(hn::Add(hn::Set(dd, basis_.forward[a]), hn::Mul(x, hn::Set(dd, basis_.right[a]))),
                               hn::Mul(y, hn::Set(dd, basis_.up[a])));
            // glm::normalize: v * (1 / sqrt(dot(v, v))), the dot as (x x + y y) + z z.
            const VD dot = hn::Add(hn::Add(hn::Mul(v[0], v[0]), hn::Mul(v[1], v[1])), hn::Mul(v[2], v[2]));
            const VD inverse = hn::Div(one, hn::Sqrt(dot));
            // clipRay().
            const glm::dvec3& eye = sc_.camera.eye();
            VD tNear = zero, tFar = hn::Set(dd, std::numeric_limits<double>::infinity()), dir[3];
            auto odd = hn::Ne(zero, zero);  // a direction clipRay() treats case by case
            for (int a = 0; a < 3; ++a) {
                dir[a] = hn::Mul(v[a], inverse);
                odd = hn::Or(odd, hn::Or(hn::Eq(dir[a], zero), hn::Not(hn::IsFinite(dir[a]))));
                const VD t0 = hn::Div(hn::Set(dd, sc_.box.lo[a] - eye[a]), dir[a]);
                const VD t1 = hn::Div(hn::Set(dd, sc_.box.hi[a] - eye[a]), dir[a]);
                const auto swap = hn::Gt(t0, t1);
                tNear = hn::Max(tNear, hn::IfThenElse(swap, t1, t0));
                tFar = hn::Min(tFar, hn::IfThenElse(swap, t0, t1));
            }
            hn::Store(hn::IfThenElseZero(hn::Not(hn::Gt(tNear, tFar)), one), dd, hit_ + j);
            hn::Store(hn::IfThenElseZero(odd, one), dd, scalar_ + j);
            hn::Store(hn::Sub(tFar, tNear), dd, length_ + j);
            // Box::toTexture() of the entry and exit points.
            for (int a = 0; a < 3; ++a) {
                const VD lo = hn::Set(dd, sc_.box.lo[a]), size = hn::Set(dd, sc_.box.hi[a] - sc_.box.lo[a]);
                const VD e = hn::Set(dd, eye[a]);
                hn::Store(hn::Div(hn::Sub(hn::Add(e, hn::Mul(tNear, dir[a])), lo), size), dd, entry_[a] + j);
                hn::Store(hn::Div(hn::Sub(hn::Add(e, hn::Mul(tFar, dir[a])), lo), size), dd, exit_[a] + j);
            }
        }
        // placeSamples<float>() and FixedStepSamples' du; glm::length as sqrt((x x + y y) + z z).
        HWY_ALIGN float exitF[3][kBatch];
        for (int a = 0; a < 3; ++a)
            for (std::size_t i = 0; i < kBatch; ++i) {
                entryF_[a][i] = static_cast<float>(entry_[a][i]);
                exitF[a][i] = static_cast<float>(exit_[a][i]);
            }
        const DF df;
        const auto length = [](const VF (&v)[3]) {
            return hn::Sqrt(hn::Add(hn::Add(hn::Mul(v[0], v[0]), hn::Mul(v[1], v[1])), hn::Mul(v[2], v[2])));
        };
        const Placement placement = sc_.options.placement;
        const bool corner = placement == Placement::EntryExitAlignCorner;
        const VF rate = hn::Set(df, static_cast<float>(sc_.options.samplingRate));
        for (std::size_t j = 0; j < size_; j += hn::Lanes(df)) {
            VF entry[3], ray[3], scaled[3];
            for (int a = 0; a < 3; ++a) {
                entry[a] = hn::Load(df, entryF_[a] + j);
                ray[a] = hn::Sub(hn::Load(df, exitF[a] + j), entry[a]);
                const float dim = sc_.dims[a];
                scaled[a] = hn::Mul(ray[a], hn::Set(df, corner ? dim - 1.f : dim));
            }
            const VF tEnd = length(ray), along = length(scaled);
            VF samples = hn::Mul(along, rate);
            if (placement == Placement::EntryExitAlign) samples = hn::Floor(samples);
            if (corner) samples = hn::Ceil(hn::Mul(rate, along));
            const VF tIncr = hn::Div(tEnd, samples);
            VF tStart = hn::Mul(hn::Set(df, 0.5f), tIncr);
            if (placement == Placement::EyeAlign) {
                VF fromEye[3];
                for (int a = 0; a < 3; ++a)
                    fromEye[a] = hn::Sub(entry[a], hn::Set(df, sc_.eyeU[a]));
                const VF steps = hn::Div(length(fromEye), tIncr);
                tStart = hn::Mul(hn::Sub(hn::Set(df, 1.f), hn::Sub(steps, hn::Floor(steps))), tIncr);
            }
            hn::Store(tEnd, df, tEnd_ + j);
            hn::Store(samples, df, samples_ + j);
            hn::Store(tIncr, df, tIncr_ + j);
            hn::Store(tStart, df, tStart_ + j);
            for (int a = 0; a < 3; ++a)
                hn::Store(hn::Div(ray[a], tEnd), df, du_[a] + j);
        }
    }

    static constexpr std::size_t kBatch = PacketScene::kMaxLanes;
    const PacketScene& sc_;
    CameraBasis basis_;
    std::size_t size_ = 0, next_ = 0;
    int pixel_[kBatch];
    // Per pixel: the texture coordinates where the ray enters and leaves the box, the world length
    // between them, and 1 where it hits the box, or takes pixelRay().
    HWY_ALIGN double entry_[3][kBatch] = {}, exit_[3][kBatch] = {}, length_[kBatch], hit_[kBatch], scalar_[kBatch];
    // And in float: the entry point, tEnd, placeSamples()' `samples`, tIncr, tStart and du.
    HWY_ALIGN float entryF_[3][kBatch], tEnd_[kBatch], samples_[kBatch], tIncr_[kBatch], tStart_[kBatch];
    HWY_ALIGN float du_[3][kBatch];
};

// The lanes' rays as start() loads them, structure of arrays; a lane without a ray has count 0. The
// march keeps a packet's rays and sums in registers and stores the sums here only for finish().
struct Lanes {
    HWY_ALIGN float tStart[kMaxLanes], tIncr[kMaxLanes];
    HWY_ALIGN float entry[3][kMaxLanes], du[3][kMaxLanes], dx[kMaxLanes];
    HWY_ALIGN float r[kMaxLanes], g[kMaxLanes], b[kMaxLanes], transparency[kMaxLanes];
    HWY_ALIGN float terminateBelow[kMaxLanes];  // the transparency that ends the ray (early_termination.h)
    HWY_ALIGN std::int32_t k[kMaxLanes], count[kMaxLanes];
    int pixel[kMaxLanes];
};

// A packet's rays in registers: constant while the packet marches.
struct PacketRays {
    VF tStart, tIncr, entry[3], du[3], dx, terminateBelow;
    VF samplesPerVoxel[3];  // along each axis, for the jumps over empty space; +inf where a ray does not move
    VI octant;              // where the distances of the ray's octant start (StencilBricks::distances())
};

template <class T, Integrator Method, EmissionModel Emission>
void marchTile(const PacketScene& sc, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts) {
    const DF df;
    const DI di;
    const VectorOps ops{df, di};
    const std::size_t n = hn::Lanes(df);
    const VectorTransferFunction tf(sc);
    const int width = x1 - x0;
    // The image holds the render's region: pixel (x0, y0) of the camera's image is at x0 - area.x, y0 - area.y.
    const PixelRegion area = renderedRegion(sc.options.region, sc.camera);
    PacketOrder order(width, y1 - y0, n);
    RayBatch batch(sc);
    Lanes L{};

    // Loads the next pixel whose ray has samples into `lane`; leaves it without a ray (count 0) when
    // the tile has none left.
    const auto start = [&](std::size_t lane) {
        L.k[lane] = L.count[lane] = 0;
        PixelSamples ray{};
        while (batch.next(order, x0, y0, width, ray)) {
            if (!ray.hit) continue;
            if (ray.worldLength > 0) ++counts.raysHit;
            // No sample: the pixel keeps the image's zeros, which is what the scalar path writes.
            if (ray.schedule.count == 0) continue;
            L.pixel[lane] = ray.pixel;
            L.tStart[lane] = ray.schedule.tStart;
            L.tIncr[lane] = ray.schedule.tIncr;
            L.count[lane] = static_cast<std::int32_t>(ray.schedule.count);
            for (int a = 0; a < 3; ++a) {
                L.entry[a][lane] = ray.entry[a];
                L.du[a][lane] = ray.du[a];
            }
            L.dx[lane] = ray.dx;
            L.terminateBelow[lane] = sc.termination.threshold<float>(ray.dx, ray.schedule.count);
            return;
        }
    };
    // Writes the pixel of `lane` from L's sums and k.
    const auto finish = [&](std::size_t lane) {
        float* out = &image.at(x0 - area.x + L.pixel[lane] % width, y0 - area.y + L.pixel[lane] / width, 0);
        out[0] = L.r[lane];
        out[1] = L.g[lane];
        out[2] = L.b[lane];
        out[3] = 1.f - L.transparency[lane];
        counts.samplesPlaced += static_cast<std::uint64_t>(L.k[lane]);
        if (L.k[lane] < L.count[lane])
            counts.terminated(sc.termination.leftOut(L.transparency[lane], L.dx[lane], L.count[lane]));
    };

    // A packet is the next n pixels with samples in PacketOrder; it ends when its last ray does.
    // (Refilling a lane as soon as its ray ends was measured 3-10 % slower on Bonsai: neighbouring rays
    // cross the same bricks, so a packet's lanes jump over empty space and evaluate together.)
    //
    // A step is two stages, software-pipelined: the march (where the lanes' samples lie, which of them
    // are in empty space, the jumps, and the interpolated value of the others) runs one sample ahead of
    // the integration (the transfer function, exp and the sums). A step is a few hundred operations, about
    // a core's reorder window, and each stage is a long chain of dependent ones: in sequence the core ran
    // little of one step beside the next; side by side, the two chains of a step are independent. The
    // march never waits on the sums: a lane that early termination ends (only the sums know) marches on
    // to no effect until the packet ends, and every sample it marches to after its end is dropped. Each lane's
    // samples are integrated in their order with the same operations, so the bits are the scalar path's.
    // Measured on Bonsai 800x600, 1 thread, AMD EPYC (Zen 4): -7 % (h = 0.5) and -5 % (h = 0.1) of the
    // time on AVX2, -9 % and -12 % on AVX-512. (A software prefetch of the stencils' cache lines a few
    // samples ahead had saved 20 % at h = 0.5 before; once the stages overlapped it cost 2 to 11 % on
    // Bonsai and Engine, both steps and both targets, and was removed.)
    VI lastBrick = hn::Set(di, -1), lastDistance = hn::Zero(di);  // the distances last gathered, and where
    std::uint64_t evaluated = 0;
    const MF none = hn::FirstN(df, 0);
    for (;;) {
        for (std::size_t lane = 0; lane < n; ++lane)
            start(lane);
        const VI count = hn::Load(di, L.count);
        VI k = hn::Zero(di);
        if (hn::AllFalse(di, hn::Lt(k, count))) break;
        PacketRays rays;
        rays.tStart = hn::Load(df, L.tStart);
        rays.tIncr = hn::Load(df, L.tIncr);
        rays.dx = hn::Load(df, L.dx);
        rays.terminateBelow = hn::Load(df, L.terminateBelow);
        for (int a = 0; a < 3; ++a) {
            rays.entry[a] = hn::Load(df, L.entry[a]);
            rays.du[a] = hn::Load(df, L.du[a]);
            // Samples per voxel (samplesInEmptyCube: an estimate, so float suffices).
            const VF perVoxel = hn::Mul(rays.du[a], hn::Set(df, sc.layout.scale[a]));
            rays.samplesPerVoxel[a] = hn::Div(hn::Set(df, 1.f), hn::Abs(hn::Mul(perVoxel, rays.tIncr)));
        }
        rays.octant = hn::Zero(di);
        for (int a = 0; a < 3; ++a)
            rays.octant = hn::IfThenElse(hn::RebindMask(di, hn::Lt(rays.du[a], hn::Zero(df))),
                                         hn::Add(rays.octant, hn::Set(di, (1 << a) * sc.octantStride)), rays.octant);
        VF r = hn::Zero(df), g = hn::Zero(df), b = hn::Zero(df), transparency = hn::Set(df, 1.f);
        // How deep a step's exponent -tau dx can reach in this packet, which picks exp_kernel's shortest
        // form that gives exp()'s bits (with a margin for the rounding of tau and of the product): at h =
        // 0.1 on Bonsai and at h = 0.5 and 0.1 on Engine, the one without a reduction.
        const VF deepest =
            hn::Mul(hn::Set(df, sc.maxTau), hn::IfThenElseZero(hn::RebindMask(df, hn::Gt(count, hn::Zero(di))), rays.dx));
        const StepDepth depth = stepDepthOf(deepest);
        MF ended = none;            // lanes early termination ended, after sample kEnded - 1
        VI kEnded = hn::Zero(di);
        MF pending = none;          // lanes whose sample the march interpolated last step, not yet integrated
        VF pendingValue = hn::Zero(df);
        VI pendingNext = hn::Zero(di);  // the index after that sample
        for (;;) {
            const MF marching = hn::RebindMask(df, hn::Lt(k, count));
            if (hn::AllFalse(df, hn::AndNot(ended, marching)) && hn::AllFalse(df, pending)) break;

            // The integration of the samples the march interpolated last step.
            if (!hn::AllFalse(df, pending)) {
                VF v[4];  // r, g, b, tau
                tf(pendingValue, pending, v);
                const VF tau = v[3];
                // RayAccumulator::add: a sample without extinction adds nothing under colour x extinction.
                const MF contributes = Emission == EmissionModel::ColourTimesExtinction
                                           ? hn::And(pending, hn::Ne(tau, hn::Zero(df)))
                                           : pending;
                // On the pending lanes, whose clamps tf() applied, tau is a lerp of non-negative finite values
                // and dx positive and finite: never NaN there.
                const VF exponent = hn::Mul(hn::Neg(tau), rays.dx);
                VF attenuation, expm1Value;
                stepExponentials<Method>(ops, depth, exponent, attenuation, expm1Value);
                VF weight;
                if constexpr (Method == Integrator::Riemann) {
                    weight = Emission == EmissionModel::ColourTimesExtinction ? hn::Mul(tau, rays.dx) : rays.dx;
                } else {
                    const VF alpha = hn::Neg(expm1Value);
                    weight = Emission == EmissionModel::ColourTimesExtinction
                                 ? alpha
                                 : hn::IfThenElse(hn::Gt(tau, hn::Zero(df)), hn::Div(alpha, tau), rays.dx);
                }
                const VF w = hn::Mul(transparency, weight);
                r = hn::IfThenElse(contributes, hn::Add(r, hn::Mul(w, v[0])), r);
                g = hn::IfThenElse(contributes, hn::Add(g, hn::Mul(w, v[1])), g);
                b = hn::IfThenElse(contributes, hn::Add(b, hn::Mul(w, v[2])), b);
                transparency = hn::IfThenElse(contributes, hn::Mul(transparency, attenuation), transparency);
                if (sc.termination.enabled()) {
                    const MF ends = hn::And(pending, hn::Lt(transparency, rays.terminateBelow));
                    kEnded = hn::IfThenElse(hn::RebindMask(di, ends), pendingNext, kEnded);
                    ended = hn::Or(ended, ends);
                }
            }

            // The march: the next sample of every lane with samples left.
            const VF t = hn::Add(rays.tStart, hn::Mul(hn::ConvertTo(df, k), rays.tIncr));
            Stencil stencil;
            {
                VF u[3];
                for (int a = 0; a < 3; ++a)
                    u[a] = hn::Add(rays.entry[a], hn::Mul(t, rays.du[a]));
                stencil = locate(sc, u, marching);
            }
            // A sample whose stencil lies in an empty brick has a transfer-function value of exactly 0
            // (occupancy_grid.h) and would add nothing: it is not evaluated. In one step, the lanes on
            // such a sample jump over the samples that certainly follow it in empty bricks and the
            // others interpolate theirs. (Interpolating only once no lane jumps, so that it runs on
            // every lane, took 10 % more CPU time on Bonsai at h = 0.5 and 0.1; waiting for 4 or 8 lanes
            // fell in between. A jump is a long chain of dependent operations, and an interpolation
            // beside it adds little to its time.)
            MF empty = none;
            if (sc.emptyDistance) {
                // The lanes often stay in their bricks from one sample to the next (at h = 0.1 on Bonsai,
                // seven times in ten for all 16 lanes): then the distances need no new gather.
                const VI brick = hn::Add(stencil.brick, rays.octant);
                if (!hn::AllTrue(di, hn::Eq(brick, lastBrick))) {
                    lastBrick = brick;
                    lastDistance = brickDistances(sc, brick);
                }
                empty = hn::And(marching, hn::RebindMask(df, hn::Ne(lastDistance, hn::Zero(di))));
            }
            const MF evaluating = hn::AndNot(empty, marching);
            if (!hn::AllFalse(df, evaluating)) {
                pendingValue = interpolate<T>(sc, stencil);
                k = hn::Add(k, hn::IfThenElseZero(hn::RebindMask(di, evaluating), hn::Set(di, 1)));
                pendingNext = k;
            }
            // The samples of lanes early termination has not ended are evaluated. Those whose value
            // makes the transfer function invisible add exactly nothing and leave the transparency as it
            // was (exp(-0) is 1), so they are not integrated: nor can they end a ray, whose threshold is
            // below 1 (early_termination.h) and so was crossed, if at all, at a sample before. On
            // Bonsai (Engine) at h = 0.5 and 0.1 that is 43 % (31 %) of the samples outside empty
            // bricks, and 35 % (26 %) of the integrations left out for every lane.
            const MF marched = hn::AndNot(ended, evaluating);
            evaluated += hn::CountTrue(df, marched);
            pending = hn::AndNot(hn::Lt(pendingValue, hn::Set(df, sc.invisibleBelow)), marched);
            if (!hn::AllFalse(df, empty)) {
                const VI jump = hn::Add(
                    samplesInEmptyCube(stencil, lastDistance, rays.du, rays.samplesPerVoxel, sc.jumpMargin),
                    hn::Set(di, 1));
                k = hn::Min(hn::Add(k, hn::IfThenElseZero(hn::RebindMask(di, empty), jump)), count);
            }
        }
        // The packet's pixels: a lane early termination ended stopped after sample kEnded - 1.
        hn::Store(r, df, L.r);
        hn::Store(g, df, L.g);
        hn::Store(b, df, L.b);
        hn::Store(transparency, df, L.transparency);
        hn::Store(hn::IfThenElse(hn::RebindMask(di, ended), kEnded, k), di, L.k);
        for (std::size_t lane = 0; lane < n; ++lane)
            if (L.count[lane] > 0) finish(lane);
    }
    counts.samplesEvaluated += evaluated;
}

// PreintegrationTable::operator()<float> in lanes: the four entries around each lane's (front, back)
// gathered per channel and interpolated bilinearly in its order; order 2 adds delta times the slopes'.
struct TableLookup {
    VI at;      // entry (i, j)'s first float
    VF fi, fj;  // the fractions along front and back
};

HWY_INLINE TableLookup lookupAt(const PreintegrationTable& table, VF front, VF back) {
    const DF df;
    const DI di;
    const VF zero = hn::Zero(df), one = hn::Set(df, 1.f), last = hn::Set(df, static_cast<float>(table.size() - 1));
    const auto locate = [&](VF s, VI& i) {
        const VF x = hn::Mul(hn::IfThenElse(hn::Gt(s, zero), hn::IfThenElse(hn::Lt(s, one), s, one), zero), last);
        i = hn::Min(truncateInRange(x), hn::Set(di, table.size() - 2));  // x lies in [0, size - 1]
        return hn::Sub(x, hn::ConvertTo(df, i));
    };
    VI i, j;
    TableLookup l;
    l.fi = locate(front, i);
    l.fj = locate(back, j);
    l.at = hn::ShiftLeft<2>(hn::Add(hn::Mul(i, hn::Set(di, table.size())), j));
    return l;
}

#if HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
constexpr std::size_t kTableLanes = hn::MaxLanes(DF());
static_assert(kTableLanes == 4 || kTableLanes == 8 || kTableLanes == 16,
              "a whole number of 128-bit blocks, at most four");

// A table entry is the 16 bytes R, G, B, depth: with x[q]'s block b holding the entry of lane q + 4 b, the
// interleaves within blocks (a 4x4 transpose each) leave channel c of lanes 4 b .. 4 b + 3 in block b of
// out[c].
HWY_INLINE void transposeBlocks(const VF (&x)[4], VF (&out)[4]) {
    const DF df;
    const hn::Repartition<std::uint64_t, DF> dw;
    const auto words = [&](VF f) { return hn::BitCast(dw, f); };
    const VF low01 = hn::InterleaveLower(df, x[0], x[1]), low23 = hn::InterleaveLower(df, x[2], x[3]);
    const VF high01 = hn::InterleaveUpper(df, x[0], x[1]), high23 = hn::InterleaveUpper(df, x[2], x[3]);
    out[0] = hn::BitCast(df, hn::InterleaveLower(dw, words(low01), words(low23)));
    out[1] = hn::BitCast(df, hn::InterleaveUpper(dw, words(low01), words(low23)));
    out[2] = hn::BitCast(df, hn::InterleaveLower(dw, words(high01), words(high23)));
    out[3] = hn::BitCast(df, hn::InterleaveUpper(dw, words(high01), words(high23)));
}

// The corners (i', j) and (i', j + 1) of the lanes' cells in channels, lane l's two entries the 32 bytes at
// v + at[l] + offset: 128-bit loads, one an entry (a gather loads its elements one by one, and its wide
// forms are slow on AMD's cores: gathering the channels, even two floats a lane at a time, cost more). On 8
// lanes an entry pair is one 256-bit load, its blocks the two corners, regrouped after the transposes.
HWY_INLINE void loadCornerPair(const float* v, const std::int32_t* at, std::ptrdiff_t offset, VF (&first)[4],
                               VF (&second)[4]) {
    const DF df;
    const auto entry = [&](std::size_t lane) { return v + at[lane] + offset; };
    if constexpr (kTableLanes == 8) {
        VF low[4], high[4], lanes0123[4], lanes4567[4];
        for (std::size_t q = 0; q < 4; ++q) {
            low[q] = hn::LoadU(df, entry(q));
            high[q] = hn::LoadU(df, entry(q + 4));
        }
        transposeBlocks(low, lanes0123);
        transposeBlocks(high, lanes4567);
        for (int c = 0; c < 4; ++c) {
            first[c] = hn::ConcatLowerLower(df, lanes4567[c], lanes0123[c]);
            second[c] = hn::ConcatUpperUpper(df, lanes4567[c], lanes0123[c]);
        }
    } else {
        // One corner: entry l + 4 b in block b of x[l].
        const auto corner = [&](std::ptrdiff_t next, VF(&out)[4]) {
            VF x[4];
            for (std::size_t q = 0; q < 4; ++q) {
                if constexpr (kTableLanes == 4) {
                    x[q] = hn::LoadU(df, entry(q) + next);
                } else {
                    const hn::Half<DF> d8;
                    const hn::Half<decltype(d8)> d4;
                    const auto block = [&](std::size_t lane) { return hn::LoadU(d4, entry(lane) + next); };
                    x[q] = hn::Combine(df, hn::Combine(d8, block(q + 12), block(q + 8)),
                                       hn::Combine(d8, block(q + 4), block(q)));
                }
            }
            transposeBlocks(x, out);
        };
        corner(0, first);
        corner(4, second);
    }
}
#endif

HWY_INLINE void interpolateTable(const float* v, const TableLookup& l, int size, VF (&out)[4]) {
    const DF df;
    const DI di;
#if HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
    HWY_ALIGN std::int32_t at[kMaxLanes];
    hn::Store(l.at, di, at);
    VF a[4][4];  // the corners (i, j), (i, j + 1), (i + 1, j), (i + 1, j + 1), each in channels
    loadCornerPair(v, at, 0, a[0], a[1]);
    loadCornerPair(v, at, 4 * static_cast<std::ptrdiff_t>(size), a[2], a[3]);
    for (int c = 0; c < 4; ++c) out[c] = lerp(lerp(a[0][c], a[1][c], l.fj), lerp(a[2][c], a[3][c], l.fj), l.fi);
#else
    const VI right = hn::Set(di, 4), down = hn::Set(di, size * 4), both = hn::Set(di, size * 4 + 4);
    for (int c = 0; c < 4; ++c) {
        const VI at = hn::Add(l.at, hn::Set(di, c));
        const VF near = lerp(hn::GatherIndex(df, v, at), hn::GatherIndex(df, v, hn::Add(at, right)), l.fj);
        const VF far = lerp(hn::GatherIndex(df, v, hn::Add(at, down)), hn::GatherIndex(df, v, hn::Add(at, both)), l.fj);
        out[c] = lerp(near, far, l.fi);
    }
#endif
}

// Pre-integration (cpu_renderer.cpp's marchSegments) on packets: each lane looks up its segments in order,
// its scalars read by the same stencils as a sample, and RayAccumulator::addSegment in lanes; a lane jumps
// over segments in the table's own empty space (sc.emptyDistance: the pre-integration StencilBricks) and
// reads its front scalar again where it lands, at the same position the segment before would have given it.
template <class T, int Order>
void marchSegmentsTile(const PacketScene& sc, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts) {
    const DF df;
    const DI di;
    const VectorOps ops{df, di};
    const std::size_t n = hn::Lanes(df);
    const PreintegrationTable& table = *sc.preintegration;
    const float* values = table.values<float>();
    const float* slopes = table.slopes<float>();
    constexpr bool secondOrder = Order == 2;
    // PreintegrationTable::operator()'s clamp of a second-order value, once per call, not per sample.
    const VF upper[4] = {hn::Set(df, table.upperBound<float>()[0]), hn::Set(df, table.upperBound<float>()[1]),
                         hn::Set(df, table.upperBound<float>()[2]), hn::Set(df, table.upperBound<float>()[3])};
    const float segmentLength = static_cast<float>(table.segmentLength());
    // Below this both ends of a segment look up exactly 0 (PreintegrationTable::invisibleBelow, less far more
    // than the float rounding of a scalar and of its cell): a round where every lane's segment lies there looks
    // nothing up.
    const VF zeroBelow = hn::Set(df, static_cast<float>(table.invisibleBelow() - 1e-5));
    const int width = x1 - x0;
    const PixelRegion area = renderedRegion(sc.options.region, sc.camera);
    PacketOrder order(width, y1 - y0, n);
    RayBatch batch(sc);
    HWY_ALIGN float tStart[kMaxLanes], tIncr[kMaxLanes], entry[3][kMaxLanes], du[3][kMaxLanes], ratio[kMaxLanes];
    HWY_ALIGN float r[kMaxLanes], g[kMaxLanes], b[kMaxLanes], transparency[kMaxLanes];
    HWY_ALIGN std::int32_t count[kMaxLanes];
    int pixel[kMaxLanes];
    std::uint64_t lookedUp = 0;  // segments looked up, of all lanes
    VF largestDelta = hn::Zero(df);  // order 2: the largest |delta| a lane's lookup asked, and the checked
    std::size_t deltaLevels = 0;     // deltas (PreintegrationTable::checkedDeltas) it is counted against
    VF deltaLevel[PreintegrationTable::kMaxDeltaLevels];
    for (const double level : table.checkedDeltas()) deltaLevel[deltaLevels++] = hn::Set(df, static_cast<float>(level));
    const auto stencilAt = [&](VF t, MF valid, const VF (&e)[3], const VF (&d)[3]) {
        VF u[3];
        for (int a = 0; a < 3; ++a)
            u[a] = hn::Add(e[a], hn::Mul(t, d[a]));
        return locate(sc, u, valid);
    };
    const auto scalarAt = [&](VF t, MF valid, const VF (&e)[3], const VF (&d)[3]) {
        return interpolate<T>(sc, stencilAt(t, valid, e, d));
    };
    for (;;) {
        std::size_t filled = 0;
        for (std::size_t lane = 0; lane < n; ++lane) {
            count[lane] = 0;
            tStart[lane] = tIncr[lane] = ratio[lane] = 0.f;
            for (int a = 0; a < 3; ++a)
                entry[a][lane] = du[a][lane] = 0.f;
            PixelSamples ray{};
            while (batch.next(order, x0, y0, width, ray)) {
                if (!ray.hit) continue;
                if (ray.worldLength > 0) ++counts.raysHit;
                if (ray.schedule.count == 0) continue;
                pixel[lane] = ray.pixel;
                tStart[lane] = ray.schedule.tStart;
                tIncr[lane] = ray.schedule.tIncr;
                count[lane] = static_cast<std::int32_t>(ray.schedule.count);
                for (int a = 0; a < 3; ++a) {
                    entry[a][lane] = ray.entry[a];
                    du[a][lane] = ray.du[a];
                }
                ratio[lane] = ray.dx / segmentLength;
                ++filled;
                break;
            }
        }
        if (filled == 0) break;
        VF e[3], d[3];
        for (int a = 0; a < 3; ++a) {
            e[a] = hn::Load(df, entry[a]);
            d[a] = hn::Load(df, du[a]);
        }
        const VF start = hn::Load(df, tStart), step = hn::Load(df, tIncr), lengthRatio = hn::Load(df, ratio);
        const VF segmentOffset = hn::Sub(start, hn::Mul(hn::Set(df, 0.5f), step));  // FixedStepSamples::segmentStart
        const VI lanesCount = hn::Load(di, count);
        const VF zero = hn::Zero(df), one = hn::Set(df, 1.f);
        // The jumps over the table's empty space (StencilBricks' pre-integration bricks): samples per voxel along
        // each axis, the octant of each ray, and which rays may jump at all: those whose step is shorter than a
        // brick along every axis, so that a segment's two ends lie in bricks that touch.
        VF samplesPerVoxel[3];
        VI octant = hn::Zero(di);
        const MF hasRay = hn::RebindMask(df, hn::Lt(hn::Zero(di), lanesCount));
        MF mayJump = hasRay;
        for (int a = 0; a < 3; ++a) {
            const VF voxelsPerStep = hn::Abs(hn::Mul(hn::Mul(d[a], hn::Set(df, sc.layout.scale[a])), step));
            samplesPerVoxel[a] = hn::Div(one, voxelsPerStep);
            // Less twice the margin of the positions' rounding, so that the true step is shorter too.
            mayJump = hn::And(mayJump, hn::Lt(voxelsPerStep, hn::Set(df, float(1 << StencilBricks::kShift) - 2 * sc.jumpMargin)));
            octant = hn::IfThenElse(hn::RebindMask(di, hn::Lt(d[a], zero)),
                                    hn::Add(octant, hn::Set(di, (1 << a) * sc.octantStride)), octant);
        }
        // A segment's depth is at most the table's bound times its length ratio, which picks exp_kernel's
        // shortest form of its attenuation (stepDepthOf).
        const StepDepth depthForm =
            stepDepthOf(hn::Mul(hn::Set(df, table.upperBound<float>()[3]), hn::IfThenElseZero(hasRay, lengthRatio)));
        // Segments of the table's length (lengthRatio 1: every segment of an equally spaced volume under Entry or
        // Eye Align) need no correction of their integral: its two expm1 and a division are left out.
        const bool unitLengths = hn::AllTrue(df, hn::Or(hn::Eq(lengthRatio, one), hn::Not(hasRay)));
        // A lane's segments end at boundaries 0 .. count; a lane without a ray (count 0) reads none.
        const VI boundaries = hn::IfThenElseZero(hn::RebindMask(di, hasRay), hn::Add(lanesCount, hn::Set(di, 1)));
        VI lastBrick = hn::Set(di, -1), lastDistance = hn::Zero(di);
        VF cr = zero, cg = zero, cb = zero, left = one;
        VI k = hn::Zero(di);               // the boundary each lane reads next
        MF haveFront = hn::FirstN(df, 0);  // lanes that read boundary k - 1, into `front`
        MF frontEmpty = haveFront;         // lanes whose boundary k - 1 lies in an empty brick
        VF front = zero;
        MF pending = hn::FirstN(df, 0);  // lanes whose segment the march read last step, not yet looked up
        VF pendingFront = zero, pendingBack = zero, pendingDelta = zero;
        const auto boundary = [&](VI at) { return hn::Add(segmentOffset, hn::Mul(hn::ConvertTo(df, at), step)); };
        // Two stages a step, as marchTile's: the march reads each lane's next boundary (or jumps) one step
        // ahead of the lookup and the sums of the segment it ended, so that the two chains run side by side.
        for (;;) {
            const MF marching = hn::RebindMask(df, hn::Lt(k, boundaries));
            if (hn::AllFalse(df, marching) && hn::AllFalse(df, pending)) break;

            // The lookup of the segments the march ended last step, and RayAccumulator::addSegment.
            if (!hn::AllFalse(df, pending)) {
                VF v[4];
                const TableLookup l = lookupAt(table, pendingFront, pendingBack);
                interpolateTable(values, l, table.size(), v);
                if constexpr (secondOrder) {
                    VF slope[4];
                    interpolateTable(slopes, l, table.size(), slope);
                    for (int c = 0; c < 4;
                         ++c)  // kept within [0, upperBound] as PreintegrationTable::operator() keeps it
                        v[c] = hn::Max(hn::Min(hn::Add(v[c], hn::Mul(pendingDelta, slope[c])), upper[c]), zero);
                }
                const MF adds = hn::AndNot(hn::And(hn::And(hn::Eq(v[3], zero), hn::Eq(v[0], zero)),
                                                   hn::And(hn::Eq(v[1], zero), hn::Eq(v[2], zero))),
                                           pending);
                if constexpr (secondOrder) {
                    const VF deltaSize = hn::Abs(pendingDelta);
                    largestDelta = hn::Max(largestDelta, hn::IfThenElseZero(adds, deltaSize));
                    counts.lookupsBeyond[0] += hn::CountTrue(df, adds);
                    // The levels ascend: past the first no lane exceeds, none does (most deviations stop at a spacing).
                    for (std::size_t level = 0; level < deltaLevels; ++level) {
                        const MF beyond = hn::And(adds, hn::Gt(deltaSize, deltaLevel[level]));
                        if (hn::AllFalse(df, beyond)) break;
                        counts.lookupsBeyond[level + 1] += hn::CountTrue(df, beyond);
                    }
                }
                if (!hn::AllFalse(df, adds)) {
                    const VF depth = hn::Mul(v[3], lengthRatio);
                    VF scale = one;
                    if (!unitLengths) {
                        const VF corrected =
                            hn::Div(exp_kernel::expm1(ops, hn::Neg(depth)), exp_kernel::expm1(ops, hn::Neg(v[3])));
                        scale = hn::IfThenElse(hn::Eq(lengthRatio, one), one,
                                               hn::IfThenElse(hn::Gt(v[3], zero), corrected, lengthRatio));
                    }
                    const VF w = hn::Mul(left, scale);
                    cr = hn::IfThenElse(adds, hn::Add(cr, hn::Mul(w, v[0])), cr);
                    cg = hn::IfThenElse(adds, hn::Add(cg, hn::Mul(w, v[1])), cg);
                    cb = hn::IfThenElse(adds, hn::Add(cb, hn::Mul(w, v[2])), cb);
                    left = hn::IfThenElse(adds, hn::Mul(left, stepAttenuation(ops, depthForm, hn::Neg(depth))), left);
                }
                pending = hn::FirstN(df, 0);
            }
            if (hn::AllFalse(df, marching)) continue;

            // The march: each lane reads boundary k, which ends its segment k - 1 where it read k - 1.
            const Stencil stencil = stencilAt(boundary(k), marching, e, d);
            // A lane whose boundary lies in an empty brick (StencilBricks' pre-integration bricks) jumps over the
            // segments whose two ends certainly lie in that cube of empty bricks (samplesInEmptyCube: boundaries
            // k .. k + m), each of which looks up exactly 0 and adds nothing, to boundary k + m, in the cube too (done
            // where the cube holds its last boundary). There it has no front: the segment ending there adds nothing.
            MF empty = hn::FirstN(df, 0), jumping = empty;
            VI m = hn::Zero(di);
            if (sc.emptyDistance) {
                const VI brick = hn::Add(stencil.brick, octant);
                if (!hn::AllTrue(di, hn::Eq(brick, lastBrick))) {
                    lastBrick = brick;
                    lastDistance = brickDistances(sc, brick);
                }
                empty = hn::And(hn::And(marching, mayJump), hn::RebindMask(df, hn::Ne(lastDistance, hn::Zero(di))));
                if (!hn::AllFalse(df, empty)) {
                    m = samplesInEmptyCube(stencil, lastDistance, d, samplesPerVoxel, sc.jumpMargin);
                    jumping = hn::And(empty, hn::RebindMask(df, hn::Gt(m, hn::Zero(di))));
                }
            }
            // Segment k - 1 is looked up unless its two ends lie in empty bricks, which touch (the step is shorter
            // than a brick along every axis).
            const MF looking = hn::AndNot(hn::And(frontEmpty, empty), hn::And(marching, haveFront));
            // The boundary's value ends that segment, or starts the next where the lane does not jump: where no lane
            // needs it, it is not read.
            if (!hn::AllFalse(df, hn::Or(looking, hn::AndNot(jumping, marching)))) {
                const VF back = interpolate<T>(sc, stencil);
                lookedUp += hn::CountTrue(df, looking);
                // Below zeroBelow both ends look up exactly 0: such a segment adds nothing and is not looked up.
                pending = hn::AndNot(hn::And(hn::Lt(front, zeroBelow), hn::Lt(back, zeroBelow)), looking);
                pendingFront = front;
                pendingBack = back;
                if (secondOrder && !hn::AllFalse(df, pending)) {
                    const VI segment = hn::Sub(k, hn::Set(di, 1));
                    const VF t = hn::Add(start, hn::Mul(hn::ConvertTo(df, segment), step));
                    pendingDelta =
                        hn::Sub(scalarAt(t, pending, e, d), hn::Mul(hn::Set(df, 0.5f), hn::Add(front, back)));
                }
                front = back;
            }
            haveFront = hn::AndNot(jumping, marching);
            frontEmpty = empty;
            const VI landing = hn::Add(k, m);
            k = hn::IfThenElse(hn::RebindMask(di, jumping),
                               hn::IfThenElse(hn::Lt(landing, lanesCount), landing, boundaries),
                               hn::Add(k, hn::IfThenElseZero(hn::RebindMask(di, marching), hn::Set(di, 1))));
        }
        hn::Store(cr, df, r);
        hn::Store(cg, df, g);
        hn::Store(cb, df, b);
        hn::Store(left, df, transparency);
        for (std::size_t lane = 0; lane < n; ++lane) {
            if (count[lane] == 0) continue;
            float* out = &image.at(x0 - area.x + pixel[lane] % width, y0 - area.y + pixel[lane] / width, 0);
            out[0] = r[lane];
            out[1] = g[lane];
            out[2] = b[lane];
            out[3] = 1.f - transparency[lane];
            counts.samplesPlaced += static_cast<std::uint64_t>(count[lane]);
        }
    }
    counts.samplesEvaluated += lookedUp;
    counts.largestDelta =
        std::max(counts.largestDelta, static_cast<double>(hn::GetLane(hn::MaxOfLanes(df, largestDelta))));
}

template <class T>
void marchTileOfType(const PacketScene& sc, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts) {
    if (sc.preintegration)
        return sc.preintegration->order() == 2 ? marchSegmentsTile<T, 2>(sc, x0, y0, x1, y1, image, counts)
                                               : marchSegmentsTile<T, 1>(sc, x0, y0, x1, y1, image, counts);
    const bool composite = sc.options.integrator == Integrator::Composite;
    if (sc.emission == EmissionModel::ColourTimesExtinction) {
        if (composite)
            marchTile<T, Integrator::Composite, EmissionModel::ColourTimesExtinction>(sc, x0, y0, x1, y1, image,
                                                                                      counts);
        else
            marchTile<T, Integrator::Riemann, EmissionModel::ColourTimesExtinction>(sc, x0, y0, x1, y1, image, counts);
    } else {
        if (composite)
            marchTile<T, Integrator::Composite, EmissionModel::Colour>(sc, x0, y0, x1, y1, image, counts);
        else
            marchTile<T, Integrator::Riemann, EmissionModel::Colour>(sc, x0, y0, x1, y1, image, counts);
    }
}

void MarchPackets(const PacketScene& sc, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts) {
    switch (sc.type) {
        case VoxelType::UInt8:
            return marchTileOfType<std::uint8_t>(sc, x0, y0, x1, y1, image, counts);
        case VoxelType::UInt16:
            return marchTileOfType<std::uint16_t>(sc, x0, y0, x1, y1, image, counts);
        case VoxelType::Float32:
            return marchTileOfType<float>(sc, x0, y0, x1, y1, image, counts);
    }
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace vri
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace vri {

HWY_EXPORT(MarchPackets);
HWY_EXPORT(TargetName);

void marchPackets(const PacketScene& scene, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts) {
    HWY_DYNAMIC_DISPATCH(MarchPackets)(scene, x0, y0, x1, y1, image, counts);
}

std::string packetTargetName() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

bool PacketScene::supports(const Scene& scene, const RenderOptions& options) {
    if (!scene.volume || !packetMethod(options)) return false;
    const Volume& v = *scene.volume;
    // The offsets gathered: voxels, and the eight octants of stencil-brick distances (StencilBricks),
    // which a thin volume (a few voxels across two axes) makes almost an eighth as many as its voxels.
    std::size_t stencilBricks = 8;
    for (int a = 0; a < 3; ++a)
        stencilBricks *= static_cast<std::size_t>((v.dims[a] - 1) / (1 << StencilBricks::kShift) + 1);
    constexpr auto most = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
    return v.dims.x >= 2 && v.byteCount() >= 4 && v.byteCount() <= most && stencilBricks + 3 <= most &&
           scene.transferFunction.points().size() <= kMaxPoints;
}

PacketScene::PacketScene(const Scene& scene, const Camera& camera, const StencilBricks* stencils,
                         const RenderOptions& options, const PreintegrationTable* preintegration)
    : camera(camera),
      box(scene.box()),
      eyeU(box.toTexture(camera.eye())),
      dims(scene.dims()),
      indexMap(scene.volume->dims, scene.convention),
      options(options),
      termination(scene.transferFunction, options, box, scene.dims()),
      emission(scene.transferFunction.emission()),
      voxels(scene.volume->bytes.data()),
      type(scene.volume->type),
      voxelBytes(static_cast<std::int32_t>(scene.volume->byteCount())),
      layout(*scene.volume, scene.convention),
      preintegration(preintegration),
      voxelLoads(vri::voxelLoads()) {
    if (stencils) {
        emptyDistance = stencils->distances().data();
        const glm::ivec3 b = stencils->bricks();
        brickStride[0] = 1;
        brickStride[1] = b.x;
        brickStride[2] = b.x * b.y;
        octantStride = b.x * b.y * b.z;
        const glm::ivec3 d = scene.volume->dims;
        jumpMargin = 0.01f + 1e-5f * static_cast<float>(std::max({d.x, d.y, d.z}));
    }
    const auto& p = scene.transferFunction.points();
    for (const auto& q : p)
        pointS.push_back(static_cast<float>(q.s));
    for (std::size_t i = 1; i + 1 < p.size(); ++i)
        innerS.push_back(pointS[i]);
    innerS.resize((innerS.size() + 3) / 4 * 4, std::numeric_limits<float>::quiet_NaN());
    const auto channels = [](const TransferFunctionPoint& q) { return std::array<double, 4>{q.r, q.g, q.b, q.tau}; };
    for (int c = 0; c < 4; ++c) {
        first[c] = static_cast<float>(channels(p.front())[c]);
        last[c] = static_cast<float>(channels(p.back())[c]);
    }
    const TransferFunction& tf = scene.transferFunction;
    maxTau = static_cast<float>(tf.largest().tau);
    // Below the last point of the leading run of invisible points, the float path's bracket is a segment
    // between two of them (or the constant below the first): a lerp of zeros. That holds up to a jump out
    // of zero too, whose left point ends the run (TransferFunction::isInvisible(s0, s1) evaluates the
    // right-continuous value at the jump and would stop one point early).
    invisibleBelow = -std::numeric_limits<float>::infinity();
    for (const auto& q : p) {
        if (!tf.isInvisible(TransferFunctionSample<double>{q.r, q.g, q.b, q.tau})) break;
        invisibleBelow = &q == &p.back() ? std::numeric_limits<float>::infinity() : static_cast<float>(q.s);
    }
    // A single point has no segment; the selects in VectorTransferFunction then always pick `first`.
    segments = std::max<std::size_t>(p.size(), 2) - 1;
    const std::size_t padded = (segments + kMaxLanes - 1) / kMaxLanes * kMaxLanes;  // whole vectors for LoadU
    for (std::size_t i = 0; i < padded; ++i) {
        const auto& a = p[std::min(i, segments - 1)];
        const auto& b = p[std::min(i, segments - 1) + (p.size() > 1 ? 1 : 0)];
        segmentStart.push_back(static_cast<float>(a.s));
        segmentWidth.push_back(static_cast<float>(b.s - a.s));
        for (int c = 0; c < 4; ++c) {
            value[c].push_back(static_cast<float>(channels(a)[c]));
            slope[c].push_back(static_cast<float>(channels(b)[c] - channels(a)[c]));
        }
    }
}

}  // namespace vri
#endif  // HWY_ONCE
