#pragma once
// Pre-integrated classification (Engel, Kraus and Ertl 2001; Röttger et al.): a table over the scalar at
// a segment's front and back of the emission-absorption integral across the segment, the scalar taken
// linear along it, so that a transfer function with narrow peaks or jumps no longer needs steps short
// enough to sample them. The second-order variant (Etiene, Kirby and Silva 2013 study its convergence)
// lets the scalar be the quadratic through front, midpoint and back; vri tabulates it as the first-order
// expansion in the midpoint's deviation delta = s_mid - (s_front + s_back) / 2, a second 2D table of the
// derivative in delta beside the first, not a 3D table (delta is O(h^2) on a smooth field, so the
// expansion's O(delta^2) adds O(h^4) per segment).
//
// Every entry is vri's exact method (exact_ray.h) on one piece of the segment's length: the integral
// split where the scalar crosses a transfer-function point and each sub-piece integrated by Gauss rules
// to `kEntryTolerance`, not a Riemann sum. The lookup interpolates bilinearly between entries; what that
// costs is measured against the same direct evaluation (check()) and reported in the stats.
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

#include "libvri/core/transfer_function.h"

namespace vri {

// One segment's integral: premultiplied colour and the optical depth across it.
template <class Real>
struct SegmentIntegral {
    Real r, g, b, depth;
};

// The largest table deviation from direct evaluation, per quantity, over the points check() tries.
struct PreintegrationError {
    double colour = 0.0;  // max over R, G, B of |lookup - direct|
    double alpha = 0.0;   // |1 - exp(-depth) looked up - the direct alpha|
    int points = 0;       // how many (front, back[, delta]) were compared
    // Order 2: the midpoint deviations |delta| compared at, in scalar units, ascending, and the largest
    // errors found at each (both signs); colour and alpha above are the largest over all of them.
    std::vector<double> deltas, colourByDelta, alphaByDelta;

    // The largest errors found at the deviations up to the first checked one at or above `largestDelta`
    // (all of them past the last): what the check says of a render whose lookups asked deviations up to it.
    std::pair<double, double> upTo(double largestDelta) const;
};

class PreintegrationTable {
public:
    static constexpr int kMinSize = 2;
    // 1024^2 entries of 4 doubles and 4 floats are 48 MiB per table (order 2 keeps two), about a million
    // exact integrals to build; the default's interpolation error is measured in the README's conventions.
    static constexpr int kMaxSize = 1024;
    static constexpr int kDefaultSize = 256;
    // The exact method's tolerance per entry: its Gauss path, far below the interpolation error.
    static constexpr double kEntryTolerance = 1e-10;

    // Integrates `tf` over segments of `segmentLength` world units for scalars on the grid i / (size - 1),
    // i = 0 .. size - 1, in parallel; order 2 adds the derivative table. Throws vri::Error on a size outside
    // [kMinSize, kMaxSize], an order other than 1 or 2, or a length that is not positive and finite.
    PreintegrationTable(const TransferFunction& tf, double segmentLength, int size, int order);

    int size() const { return size_; }
    // The second-order table's derivative in delta is the centred difference over +-kSlopeStep of the
    // table's spacing: the differences of exact integrals (each within kEntryTolerance), so the slope's
    // rounding is about kEntryTolerance / step, and a jump in the transfer function is crossed, not
    // differentiated.
    static constexpr double kSlopeStep = 0.25;
    // The largest value of R, G, B and depth any segment of segmentLength() can have under the TF: depth
    // <= L tau_max; colour <= C_max (1 - exp(-L tau_max)) when colour is weighted by extinction (the
    // integral of C tau T is at most C_max times that of tau T), C_max L when colour is emitted alone.
    // Every entry lies within it (a convex combination of exact integrals), so only the second-order
    // correction meets it.
    template <class Real>
    const Real* upperBound() const;
    int order() const { return order_; }
    double segmentLength() const { return length_; }

    // The integral over a segment of segmentLength() from scalar `front` to `back` (each clamped to
    // [0, 1], the table's domain), `delta` the midpoint's deviation (order 2; ignored by order 1). Each
    // second-order value is kept within [0, upperBound()], what a segment's integral can physically be:
    // beside a transfer-function jump the linear expansion in delta extrapolates a steep slope without
    // bound (on paper-b-failures' spiky TF at h = 2 it gave colours of 1.5e6), while on smooth data it
    // stays inside and the clamp changes nothing.
    template <class Real>
    SegmentIntegral<Real> operator()(Real front, Real back, Real delta) const {
        const Real* v = values<Real>();
        const Real last = static_cast<Real>(size_ - 1);
        auto locate = [&](Real s, int& i) {
            const Real x = (s > Real(0) ? (s < Real(1) ? s : Real(1)) : Real(0)) * last;
            i = static_cast<int>(x);
            if (i > size_ - 2) i = size_ - 2;
            return x - static_cast<Real>(i);
        };
        int i = 0, j = 0;
        const Real fi = locate(front, i), fj = locate(back, j);
        const std::size_t at = (static_cast<std::size_t>(i) * size_ + j) * 4, row = static_cast<std::size_t>(size_) * 4;
        Real out[4];
        for (int c = 0; c < 4; ++c) {
            const Real near = lerp(v[at + c], v[at + 4 + c], fj), far = lerp(v[at + row + c], v[at + row + 4 + c], fj);
            out[c] = lerp(near, far, fi);
        }
        if (order_ == 2) {
            const Real* d = slopes<Real>();
            const Real* top = upperBound<Real>();
            for (int c = 0; c < 4; ++c) {
                const Real near = lerp(d[at + c], d[at + 4 + c], fj), far = lerp(d[at + row + c], d[at + row + 4 + c], fj);
                const Real value = out[c] + delta * lerp(near, far, fi);
                out[c] = value > Real(0) ? (value < top[c] ? value : top[c]) : Real(0);
            }
        }
        return {out[0], out[1], out[2], out[3]};
    }

    // The direct evaluation a lookup approximates: the exact method on the segment, the scalar the
    // quadratic through front, the midpoint front/2 + back/2 + delta and back.
    static SegmentIntegral<double> direct(const TransferFunction& tf, double segmentLength, double front, double back,
                                          double delta);
    // The midpoint deviations order 2 is checked at (each with both signs): in table spacings, from a quarter,
    // where the slope's expansion is close, through those of a segment across a sharp bend of the data, where
    // the first-order expansion in delta drifts (an outside audit found 4x the error reported from +-1/4
    // alone at 2.5 spacings); then in scalar units, up to a segment across a whole feature thinner than the
    // step, where it no longer means anything; last the largest a cell centre admits (1 - a spacing: the
    // midpoint at one end of [0, 1], the ends at the other).
    static constexpr double kCheckedSpacings[] = {0.25, 1.0, 4.0, 16.0};
    static constexpr double kCheckedFractions[] = {0.125, 0.25, 0.5};
    // 0, the spacings and fractions, and the widest: what the counters of a render's deviations are sized by.
    static constexpr int kMaxDeltaLevels = 2 + std::size(kCheckedSpacings) + std::size(kCheckedFractions);
    // The |delta| check() compares at, in scalar units, ascending and each once: 0 and, for order 2, the
    // above below 1 - a spacing and then that; at most kMaxDeltaLevels.
    const std::vector<double>& checkedDeltas() const { return deltaLevels_; }

    // Lookups in double against direct() at the centres of the table's cells (per axis at most 64 evenly
    // spread and those of the transfer function's points), with delta = 0 and, for order 2, each of
    // kCheckedDeltas and the whole range, where the midpoint's scalar lies in [0, 1] as a render's does: a
    // measured largest error over those points, not a bound; `deltas` says where.
    PreintegrationError check(const TransferFunction& tf) const;

    // True when every lookup whose front and back scalars lie in [s0, s1] is exactly 0 in all four values
    // (every entry, and slope, it could read is 0), so that a segment there adds nothing, bit for bit
    // (RayAccumulator::addSegment): the table's own empty space, which can be wider or narrower than the
    // transfer function's, as interpolation reads the neighbouring entries. Between two such ranges that
    // overlap, a lookup is 0 too (they lie in one run of zero entries), which is what lets a march skip
    // segments whose ends lie in neighbouring empty bricks.
    bool isInvisible(double s0, double s1) const;
    // The scalar below which every lookup is exactly 0: isInvisible(0, s) for every s below it (-infinity where
    // the table's first entry is not 0: a scalar below 0 reads it too). Scalars in that leading run, usually the air around a volume's object,
    // cost the packet engine no lookup.
    double invisibleBelow() const;

    template <class Real>
    const Real* values() const;
    template <class Real>
    const Real* slopes() const;

private:
    template <class Real>
    static Real lerp(Real a, Real b, Real t) {
        return a + t * (b - a);
    }

    int size_, order_;
    double length_;
    // Entry (i, j), front scalar i / (size - 1) and back j / (size - 1): R, G, B, depth at ((i size) + j) 4.
    std::vector<double> values_, slopes_;
    std::vector<float> valuesFloat_, slopesFloat_;  // the same, rounded once
    double upper_[4];
    float upperFloat_[4];
    // Per index, the run of zero entries it belongs to (findZeroRuns), -1 for none.
    std::vector<int> zeroRun_;
    void findZeroRuns();
    std::vector<double> deltaLevels_;
};

template <>
inline const double* PreintegrationTable::upperBound<double>() const { return upper_; }
template <>
inline const float* PreintegrationTable::upperBound<float>() const { return upperFloat_; }

template <>
inline const double* PreintegrationTable::values<double>() const { return values_.data(); }
template <>
inline const float* PreintegrationTable::values<float>() const { return valuesFloat_.data(); }
template <>
inline const double* PreintegrationTable::slopes<double>() const { return slopes_.data(); }
template <>
inline const float* PreintegrationTable::slopes<float>() const { return slopesFloat_.data(); }

}  // namespace vri
