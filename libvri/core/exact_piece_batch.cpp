// The exact method's pieces formed in batches (exact_piece_batch.h). Highway compiles the part between
// HWY_BEFORE_NAMESPACE and HWY_AFTER_NAMESPACE once per target (foreach_target.h re-includes this
// file); the rest, once. Each lane performs exact_reference.cpp's GridWalker formulas and cubic.h's
// trilinearAlongSegment in their order: std::clamp as its two compare-and-selects, zeros added where the
// scalar code adds to a zeroed coefficient.
#include "libvri/core/exact_piece_batch.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "libvri/core/exact_piece_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <limits>

HWY_BEFORE_NAMESPACE();
namespace vri {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using Poly = V[4];

// std::clamp(x, lo, hi) is min(max(x, lo), hi) with max(a, b) = a < b ? b : a, min(a, b) = b < a ? b : a.
HWY_INLINE V clampAsStd(V x, V lo, V hi) {
    const V atLeast = hn::IfThenElse(hn::Lt(x, lo), lo, x);
    return hn::IfThenElse(hn::Lt(hi, atLeast), hi, atLeast);
}

// cubic.h's lerp: r = a + w (b - a) with w = w0 + dw sigma, each product raising the degree by one.
HWY_INLINE void lerp(const Poly& a, const Poly& b, V w, V dw, Poly& r) {
    const D d;
    for (int k = 0; k < 4; ++k) r[k] = hn::Zero(d);
    for (int k = 0; k < 4; ++k) {
        const V diff = b[k] - a[k];
        r[k] = r[k] + (a[k] + w * diff);
        if (k + 1 < 4) r[k + 1] = r[k + 1] + dw * diff;
    }
}

void FormPieceCubics(PieceBatch& b, int count, const PieceFrame& f) {
    const D d;
    const int lanes = static_cast<int>(hn::Lanes(d));
    const int padded = (count + lanes - 1) / lanes * lanes;
    for (int j = count; j < padded; ++j) {  // a piece of a constant cell: finite everywhere, then ignored
        for (int k = 0; k < 8; ++k) b.corner[k][j] = 0.0;
        for (int a = 0; a < 3; ++a) b.cell[a][j] = 0.0;
        b.phiA[j] = b.phiB[j] = b.magnitude[j] = 0.0;
    }
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0), infinity = hn::Set(d, std::numeric_limits<double>::infinity()),
            negativeInfinity = hn::Set(d, -std::numeric_limits<double>::infinity());
    const V lo = hn::Set(d, f.lo), invRange = hn::Set(d, f.invRange);
    const V loScale = hn::Abs(lo);
    for (int j = 0; j < padded; j += lanes) {
        const V phiA = hn::Load(d, b.phiA + j), phiB = hn::Load(d, b.phiB + j);
        V w0[3], dw[3];
        for (int a = 0; a < 3; ++a) {
            V wA = zero, wB = zero;
            if (f.varies[a]) {
                const V entry = hn::Set(d, f.entry[a]), delta = hn::Set(d, f.delta[a]);
                const V maxCoord = hn::Set(d, f.maxCoord[a]), cell = hn::Load(d, b.cell[a] + j);
                wA = clampAsStd(clampAsStd(entry + phiA * delta, zero, maxCoord) - cell, zero, one);
                wB = clampAsStd(clampAsStd(entry + phiB * delta, zero, maxCoord) - cell, zero, one);
            }
            w0[a] = wA;
            dw[a] = wB - wA;
            hn::Store(wA, d, b.w0[a] + j);
            hn::Store(wB, d, b.w1[a] + j);
        }
        Poly x[4], y[2], s;
        V corner[8];
        for (int k = 0; k < 8; ++k) corner[k] = hn::Load(d, b.corner[k] + j);
        for (int i = 0; i < 4; ++i) {  // (dy, dz) = (i & 1, i >> 1)
            const Poly a = {corner[2 * i], zero, zero, zero};
            const Poly c = {corner[2 * i + 1], zero, zero, zero};
            lerp(a, c, w0[0], dw[0], x[i]);
        }
        for (int i = 0; i < 2; ++i) lerp(x[2 * i], x[2 * i + 1], w0[1], dw[1], y[i]);
        lerp(y[0], y[1], w0[2], dw[2], s);
        const V c0 = (s[0] - lo) * invRange, c1 = s[1] * invRange, c2 = s[2] * invRange, c3 = s[3] * invRange;
        hn::Store(c0, d, b.c[0] + j);
        hn::Store(c1, d, b.c[1] + j);
        hn::Store(c2, d, b.c[2] + j);
        hn::Store(c3, d, b.c[3] + j);
        const V magnitude = hn::Load(d, b.magnitude + j);
        const V scale = hn::Abs(c0) + hn::Abs(c1) + hn::Abs(c2) + hn::Abs(c3) + (magnitude + loScale) * invRange;
        hn::Store(scale, d, b.sScale + j);
        // The corners that weigh on the piece: along an axis the ray does not move along, whose weight is
        // then exactly the model's, constant, those on its far side weigh nothing where it is 0, and those on
        // its near side where it is 1. Where the ones that weigh hold one value and the cubic is that value's
        // scalar, constant, the cubic is the model's scalar exactly. (Where the ray moves along an axis, a
        // weight that rounds to 0 at both ends of a piece may not be 0 between them: all its corners weigh.)
        V lowest = infinity, highest = negativeInfinity;
        for (int k = 0; k < 8; ++k) {
            auto weighs = hn::Eq(zero, zero);  // all true
            for (int a = 0; a < 3; ++a)
                if (!f.varies[a] || f.delta[a] == 0.0)
                    weighs = hn::AndNot(hn::Eq(w0[a], (k >> a & 1) ? zero : one), weighs);
            lowest = hn::Min(lowest, hn::IfThenElse(weighs, corner[k], infinity));
            highest = hn::Max(highest, hn::IfThenElse(weighs, corner[k], negativeInfinity));
        }
        const auto exact = hn::And(hn::And(hn::Eq(lowest, highest), hn::Eq(c0, (lowest - lo) * invRange)),
                                   hn::And(hn::And(hn::Eq(c1, zero), hn::Eq(c2, zero)), hn::Eq(c3, zero)));
        hn::Store(hn::IfThenElseZero(exact, one), d, b.exact + j);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace vri
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace vri {

HWY_EXPORT(FormPieceCubics);

void formPieceCubics(PieceBatch& batch, int count, const PieceFrame& frame) {
    HWY_DYNAMIC_DISPATCH(FormPieceCubics)(batch, count, frame);
}

}  // namespace vri
#endif  // HWY_ONCE
