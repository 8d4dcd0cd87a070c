// The exact method's batched Gauss rules (exact_gauss_batch.h). Highway compiles the part between
// HWY_BEFORE_NAMESPACE and HWY_AFTER_NAMESPACE once per target (foreach_target.h re-includes this
// file); the rest, once. The formulas are exact_ray.cpp's, lane by lane; its error analysis holds here.
#include "libvri/core/exact_gauss_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "libvri/core/exact_gauss_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "libvri/core/gauss_error_bound.h"

HWY_BEFORE_NAMESPACE();
#include "libvri/core/exp_kernel.h"          // once per target, see there
#include "libvri/core/gauss_bound_kernel.h"  // once per target, see there
#include "libvri/core/segment_kernel.h"      // once per target, see there

namespace vri {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VI = hn::Vec<DI>;
using M = hn::Mask<D>;

constexpr int kMaxGaussPanels = 64;

// exp_kernel.h's and gauss_bound_kernel.h's operations, lane by lane.
struct VectorOps {
    using Scalar = double;
    D d;
    DI di;
    V set(double c) const { return hn::Set(d, c); }
    V abs(V x) const { return hn::Abs(x); }
    V max(V a, V b) const { return hn::Max(a, b); }
    V select(M m, V a, V b) const { return hn::IfThenElse(m, a, b); }
    V clamp(V x, V lo, V hi) const { return hn::Min(hi, hn::Max(lo, x)); }
    M isNaN(V x) const { return hn::IsNaN(x); }
    // k is an integer of magnitude below 2^51: adding 1.5 2^52 puts it in the low bits of the sum's
    // significand, exactly, and subtracting the constant's bits leaves k. Two operations on every target,
    // where ConvertTo to int64 takes about twenty on AVX2, which has no such conversion.
    VI toInt(V k) const {
        const V shifter = hn::Set(d, 6755399441055744.0);  // 1.5 2^52
        return hn::Sub(hn::BitCast(di, hn::Add(k, shifter)), hn::BitCast(di, shifter));
    }
    VI halve(VI k) const { return hn::ShiftRight<1>(k); }
    V pow2(VI k) const { return hn::BitCast(d, hn::ShiftLeft<52>(hn::Add(k, hn::Set(di, 1023)))); }
};

// The fewest panels of the 2- or 3-point rule whose bound reaches `allowed`, for a sub-piece that none
// of the few cheapest rules reached (the cheapest n k wins). Returns n = 0 for none.
struct Choice {
    int n = 0, k = 0;
    double shrink = 1.0;
};
Choice manyPanels(double ell, const double bound[3], double allowed) {
    Choice best;
    for (int n = 3; n >= 2; --n) {
        // k^2n must reach the ratio: k from its 2n-th root by square and cube roots, k^-2n from products
        // (k^2n is exact for k <= 64), without pow, which took more time than the rest of the choice.
        const double ratio = ell * bound[n - 1] / allowed;
        static_assert(kMaxGaussPanels == 64, "2^36 and 2^24 are 64^6 and 64^4");
        if (!(ratio < (n == 3 ? 0x1p36 : 0x1p24))) continue;
        int k = std::max(1, static_cast<int>(n == 3 ? std::sqrt(std::cbrt(ratio)) : std::sqrt(std::sqrt(ratio))));
        auto shrinkOf = [n](int panels) {
            const double square = static_cast<double>(panels) * panels;
            return 1.0 / (n == 3 ? square * square * square : square * square);
        };
        while (k < kMaxGaussPanels && !(ell * bound[n - 1] * shrinkOf(k) <= allowed)) ++k;
        if (!(ell * bound[n - 1] * shrinkOf(k) <= allowed)) continue;
        if (best.n == 0 || n * k < best.n * best.k) best = {n, k, shrinkOf(k)};
    }
    return best;
}

// The sums of each sub-piece are in units of the transparency in front of it, like the adaptive
// quadrature's in exact_ray.cpp. The rounding terms are that quadrature's for an interval, with the
// transparency on it at most transparencyMax = 1 + 2 depthError (>= exp(depthError), the most the rounding
// of D can lift it). The integrand is evaluated through s: tau and C are linear in it on the sub-piece,
// v + m (s - sA), so a node costs one cubic and four products instead of four cubics. Its rounding is within
// the coefficient form's bound (alongSegment): Horner on s errs by <= 6 u sum|s_k|, and
// |m| sum|s_k| <= sum|coefficients| + |v| + |m sA|, the terms that bound covers 16 times. The exp of the
// transparencies errs by at most 1 ulp (exp_kernel.h), within the 2 u the analysis allows it.
void IntegrateGaussBatch(GaussBatch& b, int count, double tolerance, bool colourTimesExtinction) {
    const D d;
    const VectorOps o;
    const int lanes = static_cast<int>(hn::Lanes(d));
    const int padded = (count + lanes - 1) / lanes * lanes;
    for (int j = count; j < padded; ++j) {  // a sub-piece of length 0: finite everywhere, then ignored
        for (int k = 0; k < 4; ++k) b.c[k][j] = b.value[k][j] = b.slope[k][j] = 0.0;
        b.ell[j] = b.sScale[j] = b.segmentS[j] = b.depthInFront[j] = 0.0;
    }
    // k^-2n for k = 1..4 (rows) and n = 1..3; the few panels of a short sub-piece are tried in the order
    // of their cost n k; a long one (the analytic field's, a thick medium's) gets the fewest panels of
    // the 2- and 3-point rules that reach the tolerance (manyPanels), up to kMaxGaussPanels.
    static constexpr double kShrink[4][3] = {
        {1.0, 1.0, 1.0}, {0x1p-2, 0x1p-4, 0x1p-6}, {1.0 / 9, 1.0 / 81, 1.0 / 729}, {0x1p-4, 0x1p-8, 0x1p-12}};
    static constexpr int kTries[][2] = {{1, 1}, {2, 1}, {1, 2}, {3, 1}, {1, 3}, {2, 2}, {1, 4}};  // {n, k}
    constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(double);
    alignas(64) double laneN[kMaxLanes], laneK[kMaxLanes], laneShrink[kMaxLanes], laneBound[3][kMaxLanes],
        laneAllowed[kMaxLanes], laneEll[kMaxLanes];
    static_assert(GaussBatch::kCapacity % kMaxLanes == 0, "whole vectors of sub-pieces");
    for (int j = 0; j < padded; j += lanes) {
        const std::array<V, 4> c = {hn::Load(d, b.c[0] + j), hn::Load(d, b.c[1] + j), hn::Load(d, b.c[2] + j),
                                    hn::Load(d, b.c[3] + j)};
        const V ell = hn::Load(d, b.ell + j), sA = hn::Load(d, b.segmentS + j);
        const V ds = segment_kernel::coefficientError(o, hn::Load(d, b.sScale + j));
        // tau along the sub-piece and the depth quartic are the ray's own (ExactRay::setUp computed them
        // when it queued the sub-piece, for done()): the lanes form them again, bit for bit, from the
        // fields the colours need anyway, rather than the batch carrying eleven more doubles per sub-piece.
        const V tauV = hn::Load(d, b.value[0] + j), tauM = hn::Load(d, b.slope[0] + j);
        const segment_kernel::Linear<V> tau = segment_kernel::alongSegment(o, c, sA, tauV, tauM, ds);
        V colourV[3], colourM[3], gMax[3], gError[3];
        std::array<V, 4> colours[3];
        for (int ch = 0; ch < 3; ++ch) {
            colourV[ch] = hn::Load(d, b.value[ch + 1] + j);
            colourM[ch] = hn::Load(d, b.slope[ch + 1] + j);
            const segment_kernel::Linear<V> colour = segment_kernel::alongSegment(o, c, sA, colourV[ch], colourM[ch], ds);
            colours[ch] = colour.p;
            segment_kernel::emissionBounds(o, colour, tau, colourTimesExtinction, gMax[ch], gError[ch]);
            hn::Store(gMax[ch], d, b.gMax[ch] + j);
        }
        const segment_kernel::Depth<V> depthQuartic = segment_kernel::depthAlong(o, tau, ell);
        const std::array<V, 5>& depth = depthQuartic.p;
        const V depthError = depthQuartic.error;
        const V transparencyMax = o.set(1.0) + o.set(2.0) * depthError;
        const std::array<V, 3> bounds =
            gauss_bound_kernel::bounds(o, colours, tau.p, colourTimesExtinction, ell, transparencyMax);
        const V front = exp_kernel::exp(o, hn::Neg(hn::Load(d, b.depthInFront + j)));
        const V allowed = o.set(tolerance) / front;
        hn::Store(front, d, b.front + j);

        // The rule. A depth error above 0.5 leaves no useful bound on the transparency: none (n = 0).
        const M noBound = hn::Not(hn::Le(depthError, o.set(0.5)));
        M chosen = noBound;
        V n = hn::Zero(d), k = hn::Zero(d), shrink = o.set(1.0);
        for (const auto& [tn, tk] : kTries) {
            const V shrinkT = o.set(kShrink[tk - 1][tn - 1]);
            const M ok = hn::AndNot(chosen, hn::Le(ell * bounds[tn - 1] * shrinkT, allowed));
            n = hn::IfThenElse(ok, o.set(tn), n);
            k = hn::IfThenElse(ok, o.set(tk), k);
            shrink = hn::IfThenElse(ok, shrinkT, shrink);
            chosen = hn::Or(chosen, ok);
        }
        if (!hn::AllTrue(d, chosen)) {  // rare: more panels, lane by lane
            hn::Store(n, d, laneN);
            hn::Store(k, d, laneK);
            hn::Store(shrink, d, laneShrink);
            hn::Store(ell, d, laneEll);
            hn::Store(allowed, d, laneAllowed);
            for (int i = 0; i < 3; ++i) hn::Store(bounds[i], d, laneBound[i]);
            alignas(64) double laneChosen[kMaxLanes];
            hn::Store(hn::IfThenElseZero(chosen, o.set(1.0)), d, laneChosen);
            for (int i = 0; i < lanes; ++i) {
                if (laneChosen[i] != 0.0) continue;
                const double laneBounds[3] = {laneBound[0][i], laneBound[1][i], laneBound[2][i]};
                const Choice choice = manyPanels(laneEll[i], laneBounds, laneAllowed[i]);
                laneN[i] = choice.n;
                laneK[i] = choice.k;
                laneShrink[i] = choice.shrink;
            }
            n = hn::Load(d, laneN);
            k = hn::Load(d, laneK);
            shrink = hn::Load(d, laneShrink);
        }

        // The rule on its k panels: the panels of all lanes in step, a lane idle once its own are done.
        const GaussRule &one = gaussRule(1), &two = gaussRule(2), &three = gaussRule(3);
        const M isOne = hn::Eq(n, o.set(1.0)), isTwo = hn::Eq(n, o.set(2.0));
        V node[3], weight[3];
        for (int i = 0; i < 3; ++i) {
            auto pick = [&](double a, double bb, double cc) {
                return hn::IfThenElse(isOne, o.set(a), hn::IfThenElse(isTwo, o.set(bb), o.set(cc)));
            };
            node[i] = pick(one.node[std::min(i, 0)], two.node[std::min(i, 1)], three.node[i]);
            weight[i] = pick(one.weight[std::min(i, 0)], two.weight[std::min(i, 1)], three.weight[i]);
        }
        const V width = o.set(1.0) / k;
        const V chosenBound = hn::IfThenElse(isOne, bounds[0], hn::IfThenElse(isTwo, bounds[1], bounds[2]));
        const V e = ell * chosenBound * shrink / k;
        const V roundingFactor = depthError + o.set(32.0 * segment_kernel::kUnit);
        V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)}, error[3] = {sum[0], sum[0], sum[0]},
          rounding[3] = {sum[0], sum[0], sum[0]};
        const int most = static_cast<int>(hn::GetLane(hn::MaxOfLanes(d, k)));
        for (int p = 0; p < most; ++p) {
            const V panel = o.set(p);
            const M panelActive = hn::Lt(panel, k);
            V f[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
            for (int i = 0; i < 3; ++i) {
                const M active = hn::And(panelActive, hn::Lt(o.set(i), n));
                const V x = (panel + node[i]) * width;
                const V sigma = (c[0] + x * (c[1] + x * (c[2] + x * c[3]))) - sA;
                V r = depth[4];
                for (int q = 3; q >= 0; --q) r = r * x + depth[q];
                V t = weight[i] * exp_kernel::exp(o, hn::Neg(r));
                if (colourTimesExtinction) t = t * (tauV + tauM * sigma);
                for (int ch = 0; ch < 3; ++ch)
                    f[ch] = hn::IfThenElse(active, f[ch] + (colourV[ch] + colourM[ch] * sigma) * t, f[ch]);
            }
            for (int ch = 0; ch < 3; ++ch) {
                const V value = ell * width * f[ch];
                sum[ch] = hn::IfThenElse(panelActive, sum[ch] + value, sum[ch]);
                error[ch] = hn::IfThenElse(panelActive, error[ch] + e, error[ch]);
                rounding[ch] = hn::IfThenElse(
                    panelActive,
                    rounding[ch] + (ell * width * transparencyMax * gError[ch] + (hn::Abs(value) + e) * roundingFactor),
                    rounding[ch]);
            }
        }
        for (int ch = 0; ch < 3; ++ch) {
            hn::Store(sum[ch], d, b.sum[ch] + j);
            hn::Store(error[ch], d, b.error[ch] + j);
            hn::Store(rounding[ch], d, b.rounding[ch] + j);
        }
        hn::Store(n, d, laneN);
        hn::Store(k, d, laneK);
        for (int i = 0; i < lanes; ++i) {
            b.panels[j + i] = static_cast<std::int32_t>(laneK[i]);
            b.nodes[j + i] = static_cast<std::int32_t>(laneN[i] * laneK[i]);
        }
    }
}

const char* BatchTargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace vri
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace vri {

HWY_EXPORT(IntegrateGaussBatch);
HWY_EXPORT(BatchTargetName);

void integrateGaussBatch(GaussBatch& batch, int count, double tolerance, bool colourTimesExtinction) {
    HWY_DYNAMIC_DISPATCH(IntegrateGaussBatch)(batch, count, tolerance, colourTimesExtinction);
}

const char* gaussBatchTarget() { return HWY_DYNAMIC_DISPATCH(BatchTargetName)(); }

}  // namespace vri
#endif  // HWY_ONCE
