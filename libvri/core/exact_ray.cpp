#include "libvri/core/exact_ray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "libvri/core/gauss_error_bound.h"
#include "libvri/core/scalar_double_ops.h"
#include "libvri/core/segment_kernel.h"

namespace vri {

namespace {

// Gauss-Kronrod rules on [-1, 1]: node[i] stands for +-node[i] for i < N - 1 and node[N - 1] = 0; the
// Gauss nodes are the odd i, with weight gauss[i / 2]. 7-15 is QUADPACK's qk15; 3-7 is the Kronrod
// extension of 3-point Gauss (exact to degree 11), half the exponentials where the tolerance allows.
template <int N>
struct KronrodRule {
    double node[N], kronrod[N], gauss[N / 2];
};
constexpr KronrodRule<8> kKronrod15 = {
    {0.991455371120812639206854697526329, 0.949107912342758524526189684047851, 0.864864423359769072789712788640926,
     0.741531185599394439863864773280788, 0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
     0.207784955007898467600689403773245, 0.0},
    {0.022935322010529224963732008058970, 0.063092092629978553290700663189204, 0.104790010322250183839876322541518,
     0.140653259715525918745189590510238, 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
     0.204432940075298892414161999234649, 0.209482141084727828012999174891714},
    {0.129484966168869693270611432679082, 0.279705391489276667901467771423780, 0.381830050505118944950369775488975,
     0.417959183673469387755102040816327}};
constexpr KronrodRule<4> kKronrod7 = {
    {0.960491268708020283423507092629080, 0.774596669241483377035853079956480, 0.434243749346802558002071502844628,
     0.0},
    {0.104656226026467265193823857192073, 0.268488089868333440728569280666710, 0.401397414775962222905051818618432,
     0.450916538658474142345110087045571},
    {0.555555555555555555555555555555556, 0.888888888888888888888888888888889}};
// Below this the 3-7 rule bisects so often that the 7-15 rule costs fewer evaluations.
constexpr double kLowOrderTolerance = 1e-8;
// A Kronrod estimate is trusted only on intervals across which the optical depth grows by at most this:
// there exp(-depth) varies by at most e^2 and every node sees it. Across a thicker interval the
// nodes can all fall where the transparency has already underflowed (tau >= 1e5 per voxel), agreeing
// on 0 while the integral is 1; such an interval is bisected or bounded by an enclosure instead.
constexpr double kResolvedDepth = 2.0;
constexpr int kMaxDepth = 40;  // bisections of one sub-piece; reached only by pathological input
// Intervals of one sub-piece: a tolerance below what rounding allows would otherwise bisect every
// interval to kMaxDepth (2^40 of them). Past it every interval is accepted with its own error.
constexpr int kMaxIntervals = 4096;
using segment_kernel::kUnit;  // unit roundoff u of double

// How many of the sorted values are <= x (upper_bound's index), and with it how many are < y
// (lower_bound's): counts without branches over the few points of a transfer function, where a binary
// search mispredicts at every step; one pass for both ends of a piece's range. Past kLinearCount
// values a binary search, so that a sub-piece costs the logarithm of the points, not their number
// (10,000 points made a 16x16 image of an 8^3 volume take 5.9 s). Both give the same counts.
constexpr std::size_t kLinearCount = 64;
std::size_t countAtMost(const std::vector<double>& sorted, double x) {
    if (sorted.size() > kLinearCount)  // a NaN is at or above no value, as in the loop
        return std::isnan(x) ? 0 : std::size_t(std::upper_bound(sorted.begin(), sorted.end(), x) - sorted.begin());
    std::size_t n = 0;
    for (double v : sorted) n += v <= x;
    return n;
}
std::pair<std::size_t, std::size_t> countAtMostAndBelow(const std::vector<double>& sorted, double x, double y) {
    if (sorted.size() > kLinearCount)
        return {countAtMost(sorted, x), std::size_t(std::lower_bound(sorted.begin(), sorted.end(), y) - sorted.begin())};
    std::size_t atMost = 0, below = 0;
    for (double v : sorted) {
        atMost += v <= x;
        below += v < y;
    }
    return {atMost, below};
}

template <std::size_t N>
double horner(const std::array<double, N>& p, double x) {
    double r = p[N - 1];
    for (std::size_t k = N - 1; k-- > 0;) r = r * x + p[k];
    return r;
}

// One Gauss-Kronrod rule on [x0, x1] for the three channels of g exp(-depth), g = C tau or C: the
// Kronrod sums in K, the Gauss sums in G (both to be multiplied by the half-width). C and tau are
// evaluated as the cubics they are and multiplied at each node, fewer operations (and roundings) than
// the degree-6 product.
template <int N>
void applyRule(const KronrodRule<N>& rule, double x0, double x1, const std::array<double, 5>& depth,
               const std::array<double, 4>& tau, const std::array<double, 4> (&colour)[3], bool colourTimesExtinction,
               double K[3], double G[3]) {
    constexpr int kNodes = 2 * N - 1;
    const double half = 0.5 * (x1 - x0), centre = 0.5 * (x0 + x1);
    // Node j < N - 1 is centre - half node[j], N - 1 + j is centre + half node[j], the last the centre.
    double x[kNodes];
    for (int i = 0; i < N - 1; ++i) {
        x[i] = centre - half * rule.node[i];
        x[N - 1 + i] = centre + half * rule.node[i];
    }
    x[kNodes - 1] = centre;
    double t[kNodes];
    for (int j = 0; j < kNodes; ++j) {
        t[j] = std::exp(-horner(depth, x[j]));
        if (colourTimesExtinction) t[j] *= horner(tau, x[j]);
    }
    for (int c = 0; c < 3; ++c) {
        double k = 0.0, gauss = 0.0;
        for (int i = 0; i < N; ++i) {
            const double f = i < N - 1 ? horner(colour[c], x[i]) * t[i] + horner(colour[c], x[N - 1 + i]) * t[N - 1 + i]
                                       : horner(colour[c], x[kNodes - 1]) * t[kNodes - 1];
            k += rule.kronrod[i] * f;
            if (i % 2 == 1) gauss += rule.gauss[i / 2] * f;
        }
        K[c] = k;
        G[c] = gauss;
    }
}

}  // namespace

ExactRay::ExactRay(const TransferFunction& tf, double tolerance)
    : tf_(tf),
      emission_(tf.emission()),
      tolerance_(tolerance),
      lowOrder_(tolerance >= kLowOrderTolerance),
      fastSplits_(tolerance >= kGaussTolerance),
      rootStart_(fastSplits_ ? RootStart::Chord : RootStart::Midpoint) {
    for (const auto& p : tf.points()) {
        if (levels_.empty() || levels_.back() != p.s) levels_.push_back(p.s);
        maxColour_ = {std::max(maxColour_[0], p.r), std::max(maxColour_[1], p.g), std::max(maxColour_[2], p.b)};
    }
    largestColour_ = std::max({1.0, maxColour_[0], maxColour_[1], maxColour_[2]});
    // The spans of s on which the TF is zero: each maximal run of zero points i..j (the TF is zero
    // between them and, past the first or last point, beyond). At a jump out of the run at p[j].s the
    // value there is the next point's, so the span stops an ulp short of it.
    const auto& points = tf.points();
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    auto zero = [&](const TransferFunctionPoint& p) {
        return p.tau == 0.0 && (colourTimesExtinction || (p.r == 0.0 && p.g == 0.0 && p.b == 0.0));
    };
    constexpr double inf = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size();) {
        if (!zero(points[i])) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < points.size() && zero(points[j + 1])) ++j;
        const double lo = i == 0 ? -inf : points[i].s;
        const double hi = j + 1 == points.size() ? inf
                          : points[j + 1].s == points[j].s ? std::nextafter(points[j].s, -inf)
                                                            : points[j].s;
        if (lo <= hi) invisibleSpans_.push_back({lo, hi});
        i = j + 1;
    }
    // With g = C tau the rest of a ray adds at most C_max T to a colour and T to alpha, so a ray may end
    // once T <= tolerance / max(1, C_max); with g = C that is necessary, not sufficient (see done()).
    terminationDepth_ = std::min(kOpaqueDepth, std::log(largestColour_ / tolerance));
    // Each of a piece's at most three monotone parts crosses each level at most once.
    splits_.reserve(3 * levels_.size() + 2);
    auto channels = [](const TransferFunctionPoint& p) { return std::array<double, 4>{p.tau, p.r, p.g, p.b}; };
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        const auto a = channels(points[i]), b = channels(points[i + 1]);
        const double inverseWidth = 1.0 / (points[i + 1].s - points[i].s);  // inf between a jump's two points
        Segment segment{points[i].s, a, {}};
        for (int k = 0; k < 4; ++k) segment.slope[k] = (b[k] - a[k]) * inverseWidth;
        segments_.push_back(segment);
    }
    segments_.push_back({points.front().s, channels(points.front()), {}});
    segments_.push_back({points.back().s, channels(points.back()), {}});
    // Per level: the left limit is the first point at it, the value from it on the last (right-continuous);
    // the segments beside it are the one ending at its first point and the one starting at its last.
    for (const auto& p : points)
        for (int k = 0; k < 4; ++k) channelMax_[k] = std::max(channelMax_[k], channels(p)[k]);
    for (std::size_t i = 0, first = 0; i < levels_.size(); ++i) {
        std::size_t last = first;
        while (last + 1 < points.size() && points[last + 1].s == levels_[i]) ++last;
        const auto left = channels(points[first]), right = channels(points[last]);
        LevelStep step;
        for (int k = 0; k < 4; ++k) {
            step.jump[k] = std::abs(right[k] - left[k]);
            step.slope[k] = std::max(first > 0 ? std::abs(segments_[first - 1].slope[k]) : 0.0,
                                     last + 1 < points.size() ? std::abs(segments_[last].slope[k]) : 0.0);
            step.high[k] = std::max(left[k], right[k]);
        }
        step.gap = std::min(i > 0 ? levels_[i] - levels_[i - 1] : inf, i + 1 < levels_.size() ? levels_[i + 1] - levels_[i] : inf);
        steps_.push_back(step);
        first = last + 1;
    }
    // Per gap: s in [level g - 1, level g) lies on segment i, from the last point at level g - 1 (its
    // value right-continuous at a jump) to the next point; below the first level and from the last
    // one on, the constants.
    for (std::size_t g = 0, atMost = 0; g <= levels_.size(); ++g) {
        while (g > 0 && atMost < points.size() && points[atMost].s <= levels_[g - 1]) ++atMost;
        const std::size_t iA = g == 0 ? 0 : atMost - 1, iB = g == 0 || g == levels_.size() ? iA : iA + 1;
        const TransferFunctionPoint& A = points[iA];
        const TransferFunctionPoint& B = points[iB];
        gaps_.push_back({iA != iB ? iA : iA == 0 ? points.size() - 1 : points.size(), zero(A) && zero(B)});
    }
    if (tolerance >= kGaussTolerance) batch_ = std::make_unique<GaussBatch>();
}

bool ExactRay::doneAtDepth(double depth, double remainingLength) const {
    return emission_ == EmissionModel::ColourTimesExtinction ||
           std::exp(-depth) * std::max(1.0, largestColour_ * remainingLength) <= tolerance_;
}

bool ExactRay::invisible(double s0, double s1) const {
    for (const auto& [lo, hi] : invisibleSpans_)
        if (s0 >= lo && s1 <= hi) return true;
    return false;
}

void ExactRay::begin() {
    queued_ = 0;
    opticalDepth_ = depthError_ = lengthWalked_ = 0.0;
    wholeWindow_ = false;
    colour_ = quadratureError_ = roundingError_ = {};
}

void ExactRay::addPiece(double length, const Cubic& s, double sScale, bool exact, const PieceCell* cell) {
    if (!(length > 0.0)) return;
    lengthWalked_ += length;
    if (exact) {  // the model's scalar, constant: its TF segment is known, with no window at any level
        const double value = s.c[0];
        if (invisible(value, value)) return;
        // But for the piece's ends: a cell face placed by rounding may move by 2 u of the piece either way, and
        // the scalar just beyond it, in the next cell, may lie on a level's other side where the value is on it.
        WrongSide faces;
        const std::size_t below = countAtMost(levels_, value);
        const double eps = wrongSideEps(sScale);
        for (const std::size_t i : {below - 1, below})
            if (i < levels_.size() && std::abs(value - levels_[i]) <= 2.0 * eps)
                addWindow(faces, length * 4.0 * kUnit, i, eps);
        integrateSubPiece(length, s, 0.0, 1.0, 0.0, faces, below);  // s exact: its coefficients carry no error
        return;
    }
    double ends[4] = {0.0}, values[4];
    // Where s' = c1 + 2 c2 x + 3 c3 x^2 cannot vanish on [0, 1], |c1| > |2 c2| + |3 c3| (with room for
    // the rounding of that test), s is monotone on the piece: no critical points to solve for, as on most
    // pieces. Only on the Gauss path: below kGaussTolerance the references keep criticalPoints' bits.
    double critical[2];
    const bool monotone = fastSplits_ && (1.0 - 0x1p-40) * std::abs(s.c[1]) > 2.0 * std::abs(s.c[2]) + 3.0 * std::abs(s.c[3]);
    const int nc = monotone ? 0 : criticalPoints(s, 0.0, 1.0, critical);
    for (int i = 0; i < nc; ++i) ends[i + 1] = critical[i];
    ends[nc + 1] = 1.0;
    const int parts = nc + 1;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i <= parts; ++i) {
        values[i] = s(ends[i]);
        lo = std::min(lo, values[i]);
        hi = std::max(hi, values[i]);
    }
    if (invisible(lo, hi)) return;  // neither extinction nor emission anywhere on the piece

    // Most pieces lie inside one TF segment, farther from its levels than rounding can reach: with their
    // ends and critical points all clear of the levels around the middle (wrongSide's test) no level
    // splits the piece and s is nowhere on a wrong side. The general path below gives these the same
    // sub-piece, segment and zero wrong side, but after more evaluations and two more searches.
    {
        const std::size_t below = countAtMost(levels_, s(0.5));
        const double margin = 2.0 * wrongSideEps(sScale);
        if ((below == 0 || lo - levels_[below - 1] > margin) && (below == levels_.size() || levels_[below] - hi > margin)) {
            integrateSubPiece(length, s, 0.0, 1.0, sScale, WrongSide{}, below);
            return;
        }
    }

    faceCount_ = 0;
    if (cell) {
        std::array<double, 8> corners;
        for (int k = 0; k < 8; ++k) corners[k] = (cell->batch.corner[k][cell->lane] - cell->lo) * cell->invRange;
        const glm::dvec3 w0(cell->batch.w0[0][cell->lane], cell->batch.w0[1][cell->lane],
                            cell->batch.w0[2][cell->lane]);
        const glm::dvec3 w1(cell->batch.w1[0][cell->lane], cell->batch.w1[1][cell->lane],
                            cell->batch.w1[2][cell->lane]);
        faceCount_ = constantFaces(corners, w0, w1, faces_);
    }
    const double eps = wrongSideEps(sScale);

    // Split where s crosses a transfer-function point: within a monotone part at most once per level,
    // in the order of the levels when s rises and in reverse when it falls.
    splits_.clear();
    splits_.push_back(0.0);
    for (int i = 0; i < parts; ++i) {
        const double a = ends[i], b = ends[i + 1], sa = values[i], sb = values[i + 1];
        const auto [countLo, countHi] = countAtMostAndBelow(levels_, std::min(sa, sb), std::max(sa, sb));
        auto first = levels_.begin() + countLo;                    // upper_bound
        auto last = levels_.begin() + std::max(countLo, countHi);  // lower_bound from first
        // At an end of the piece on a face of its cell whose corners hold a level, the computed s may cross the
        // level within rounding of the face where s only touches it there. The face tells (faceWidth): the split
        // nearest that end is not made where s stays on the part's side of the level but for the face's
        // window, which the sub-piece's wrong side then counts. `above`: the part's side is above the level.
        const auto touchesOnly = [&](double at, double into, double sAt, double level, bool above) {
            if (!(std::abs(sAt - level) <= 2.0 * eps)) return false;
            const double regular = wrongSideWidth(s, at, sAt, into, into, level, above, eps);
            const double end = at < into ? at + regular : at - regular;
            return faceWidth(level, at, end, above, eps) < std::abs(end - at);
        };
        const bool rising = sa < sb;
        if (faceCount_ > 0 && b == 1.0 && last != first &&
            (rising ? touchesOnly(b, a, sb, *(last - 1), false) : touchesOnly(b, a, sb, *first, true)))
            rising ? --last : ++first;
        if (faceCount_ > 0 && a == 0.0 && last != first &&
            (rising ? touchesOnly(a, b, sa, *first, true) : touchesOnly(a, b, sa, *(last - 1), false)))
            rising ? ++first : --last;
        auto split = [&](double level) {
            splits_.push_back(std::max(solveMonotone(s, level, a, b, rootStart_), splits_.back()));
        };
        if (sa < sb)
            for (auto it = first; it != last; ++it) split(*it);
        else
            for (auto it = last; it != first;) split(*--it);
    }
    splits_.push_back(1.0);
    for (std::size_t i = 0; i + 1 < splits_.size(); ++i)
        if (splits_[i + 1] > splits_[i]) {
            const double a = splits_[i], b = splits_[i + 1];
            const std::size_t below = countAtMost(levels_, s(0.5 * (a + b)));  // levels <= s at the middle
            integrateSubPiece(length, s, a, b, sScale, wrongSide(length, s, a, b, sScale, parts, ends, below), below);
        }
}

// Where s may lie beyond its segment. A sub-piece [a, b] is integrated with the TF segment [L_lo, L_hi]
// that holds s at its middle, but s is only known to eps = 48 u sScale (its coefficients to 32 u sScale,
// see below, and Horner's evaluation to 8 u sScale) and a split to where the computed s crosses the level
// to an ulp: wherever the computed s comes within 2 eps of L_lo or L_hi, the exact s may be on the other
// side. Nearest a level the computed s is at the sub-piece's ends and at the critical points inside it
// (between them it is monotone): each of these within 2 eps of a level is a place where s may be on the
// wrong side. Around an end the place is a window: with d0 = |s'| there and |s''| <= M2 = 2|c2| + 6|c3|,
// s' keeps its sign and |s'| >= d0 / 2 over w = 2 (r + 3 eps) / d0 (r the end's distance from the level)
// when M2 w <= d0 / 2, so s has left the level by more than 2 eps at the window's far side (checked), and
// beyond it until the next critical point or end (checked as well). Where the slope shows no window (s
// leaving the level slowly, as from a cell face whose corners all sit on it), s is still monotone up to
// the nearest critical point: if it is clear of the level there, the window ends where bisection finds it
// clear. Where neither shows one (s nearly tangent to the level all along, or constant on it but not known
// exactly), and around a critical point within 2 eps of a level, the whole sub-piece (counted per ray:
// wholeSubPieceWindow). A piece whose cubic is the model's scalar itself has no window (addPiece). Where
// a face of the piece's cell holds the level's value at its four corners, s's side is that of a quadratic
// known to its own, far smaller, rounding (faceWidth): each of these windows narrows to where that is
// unknown, and a split within rounding of the face, where s only touches the level, is not made (addPiece).
// On such a place |s - L| <= 4 eps, so the value used there (the segment's v + m (s - s_A)) and the TF's
// differ per channel by at most the jump at L plus 8 eps times the steeper slope beside it, and the TF's
// value is at most the larger value at L plus that (levels closer than 8 eps: the TF's largest value).
// Over a width w in the piece that changes the optical depth by length w dtau and g by dg (g = C tau:
// dC (tau_high + dtau) + (C_high + dC) dtau); a misplaced jump is the jump's height over w, a misplaced
// kink only the slopes over 8 eps, which on ordinary scenes adds nothing visible to the bound.
ExactRay::WrongSide ExactRay::wrongSide(double length, const Cubic& s, double a, double b, double sScale, int parts,
                                        const double* ends, std::size_t below) const {
    WrongSide r;
    const double eps = wrongSideEps(sScale);
    const double sa = s(a), sb = s(b);
    // From each end, s is monotone up to the nearest critical point inside the sub-piece (or the other end).
    double afterA = b, beforeB = a;
    for (int k = 1; k < parts; ++k)
        if (ends[k] > a && ends[k] < b) {
            afterA = std::min(afterA, ends[k]);
            beforeB = std::max(beforeB, ends[k]);
        }
    for (int side = 0; side < 2; ++side) {
        // Side 0: the level under the segment (s must stay above it); side 1: the level over it.
        if (side == 0 ? below == 0 : below == levels_.size()) continue;
        const std::size_t i = side == 0 ? below - 1 : below;
        const double level = levels_[i];
        const bool above = side == 0;
        auto near = [&](double value) { return !((above ? value - level : level - value) > 2.0 * eps); };
        // Around an end, s's window, narrowed where a constant face of the cell shows more.
        auto endWidth = [&](double at, double sAt, double into, double monotoneTo) {
            const double regular = wrongSideWidth(s, at, sAt, into, monotoneTo, level, above, eps);
            return faceCount_ == 0 || regular == 0.0
                       ? regular
                       : faceWidth(level, at, into > at ? at + regular : at - regular, above, eps);
        };
        double width = 0.0;
        if (near(sa)) width += endWidth(a, sa, b, afterA);
        if (near(sb)) width += endWidth(b, sb, a, beforeB);
        for (int k = 1; k < parts; ++k)
            if (ends[k] > a && ends[k] < b && near(s(ends[k]))) width = faceWidth(level, a, b, above, eps);
        width = std::min(width, b - a);
        if (width == 0.0) continue;
        r.whole = r.whole || width == b - a;
        addWindow(r, length * width, i, eps);
    }
    return r;
}

// Where a face of the piece's cell holds one scalar v at the level, or just beyond it on the side s must be
// on, s - level = F G + (v - level) with F >= 0 and zero at most at one point (constant_face.h): s is on its
// side wherever G is. With G monotone over the stretch from `at` to `into` (no critical point inside) and
// clear of 0 on that side by twice its rounding at one end of it, G stays clear from where bisection finds
// it clear to that end: the window is the rest (none where G is clear at both ends, all of the stretch at
// neither). F itself can be negative where the model's weight overshoots the face, at sigma = 1 only
// (w0 + (w1 - w0) sigma with the difference rounded): by at most u of the piece.
double ExactRay::faceWidth(double level, double at, double into, bool above, double eps) const {
    const double span = std::abs(into - at), lo = std::min(at, into), hi = std::max(at, into);
    double width = span;
    for (int f = 0; f < faceCount_; ++f) {
        const ConstantFace& face = faces_[f];
        if (std::abs(face.value - level) > 2.0 * eps || (face.value != level && (face.value > level) != above))
            continue;
        double critical[2];
        if (criticalPoints(face.g, lo, hi, critical) > 0) continue;
        const double gEps = wrongSideEps(face.scale);
        const auto clear = [&](double x) { return (above ? face.g(x) : -face.g(x)) > 2.0 * gEps; };
        const bool clearAt = clear(at), clearInto = clear(into);
        if (clearAt && clearInto) width = 0.0;
        if (clearAt == clearInto) continue;
        double inside = clearAt ? into : at, outside = clearAt ? at : into;  // G is unclear at one end only
        for (int i = 0; i < 64 && std::abs(outside - inside) > 0x1p-52 * span; ++i) {
            const double middle = 0.5 * (inside + outside);
            (clear(middle) ? outside : inside) = middle;
        }
        width = std::min(width, std::abs(outside - (clearAt ? into : at)));
    }
    return width < span && hi == 1.0 ? std::min(span, width + 2.0 * kUnit) : width;
}

// What a width `span` (world units) of a piece beside level i, where s may lie on the level's other side,
// adds to the optical depth's and the colour's uncertainty (see wrongSide).
void ExactRay::addWindow(WrongSide& r, double span, std::size_t i, double eps) const {
    const LevelStep& step = steps_[i];
    const bool apart = step.gap > 8.0 * eps;
    double change[4], high[4];
    for (int k = 0; k < 4; ++k) {
        change[k] = apart ? step.jump[k] + 8.0 * eps * step.slope[k] : channelMax_[k];
        high[k] = apart ? step.high[k] + 8.0 * eps * step.slope[k] : channelMax_[k];
    }
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    r.depth += span * change[0];
    for (int c = 0; c < 3; ++c) {
        const double dg = colourTimesExtinction
                              ? change[c + 1] * (high[0] + change[0]) + (high[c + 1] + change[c + 1]) * change[0]
                              : change[c + 1];
        r.colour[c] += span * dg;
        r.seen[c] += span * (colourTimesExtinction ? (high[c + 1] + change[c + 1]) * (high[0] + change[0])
                                                   : high[c + 1] + change[c + 1]);
    }
}

// eps = 48 u sScale: see above.
double ExactRay::wrongSideEps(double sScale) { return 48.0 * kUnit * sScale; }

// The window around `at`, where s is sAt, (towards `into`) in which s may be on the wrong side of `level`
// (above: s must exceed it), or the whole distance to `into` where no window can be shown (see wrongSide).
double ExactRay::wrongSideWidth(const Cubic& s, double at, double sAt, double into, double monotoneTo, double level,
                                bool above, double eps) const {
    const double span = std::abs(into - at);
    const auto beyond = [&](double x) {  // s at x is clear of the level, on the right side
        const double v = s(x);
        return (above ? v - level : level - v) > 2.0 * eps;
    };
    const double d0 = std::abs(s.derivative(at)), r = std::abs(sAt - level);
    const double curvature = 2.0 * std::abs(s.c[2]) + 6.0 * std::abs(s.c[3]);
    const double w = 2.0 * (r + 3.0 * eps) / d0;
    if (w < span && curvature * w <= 0.5 * d0 && beyond(into > at ? at + w : at - w)) return w;
    // No window from the slope (s leaves the level slowly, as from a cell face whose corners all sit on it):
    // on the stretch to `monotoneTo` the computed s is monotone, so where it is clear of the level it stays
    // clear up to there; bisect for that place.
    if (!beyond(monotoneTo)) return span;
    double inside = at, clear = monotoneTo;
    for (int i = 0; i < 64 && std::abs(clear - inside) > 0x1p-52 * span; ++i) {
        const double middle = 0.5 * (inside + clear);
        (beyond(middle) ? clear : inside) = middle;
    }
    return std::abs(clear - at);
}

// Error analysis. The result is exact for the model (trilinear field, piecewise-linear TF, along the
// ray as computed) up to (1) the quadrature and (2) rounding, bounded with u = 2^-53 as follows, the
// constants being generous counts of the operations involved:
//  - quadrature, Gauss rule (exact_gauss_batch.cpp): the remainder bound of gauss_error_bound.h holds for the
//    computed polynomials whatever their size; exp(-D) <= 1 + 2 depthError on [0, 1] covers a D that
//    the rounding of tau takes below 0.
//  - quadrature, adaptive: on an interval across which the optical depth grows by at most kResolvedDepth, the
//    integrand is smooth at the interval's scale and |K - G| estimates the error (an overestimate: the
//    Kronrod rule is far more accurate than its Gauss rule). Elsewhere, or where that estimate stays
//    too large, an enclosure that holds for any extinction: with C_low..C_high the range of C on
//    [x0, x1] (at its ends or where s' = 0, C being linear in s), g = C tau integrates to C_low..C_high times
//    T(x0) - T(x1) (tau T ell dlambda = -dT), and g = C to C_low..C_high times ell (x1 - x0) T(x1)..T(x0).
//  - s: its cubic comes from the corner values through three lerps, the normalisation and the Taylor
//    shift; each coefficient carries at most ~20 roundings of terms below sScale: |ds| <= 32 u sScale.
//  - tau, C (cubics in the sub-piece variable): forming v_A + m (s - s_A) and evaluating by Horner
//    adds <= 16 u (sum|coefficients| + |v_A| + |m s_A|); the error of s enters times the TF slope |m|.
//  - g = C tau (or C): <= dC |tau| + |C| dtau + 16 u |C| |tau|, with |C|, |tau| bounded by the sums of
//    their coefficients, times an interval's length and largest transparency.
//  - optical depth: the quartic integral of tau, error <= lambda ell (dtau + 8 u sum|tau|) at lambda,
//    plus u times the running sum per addition; the transparency exp(-depth) in front of a sub-piece
//    then has relative error <= depthError + 2 u, and so has every contribution behind it.
//  - a split misplaced by rounding (a root to within an ulp, a cell face) moves the TF segment or the
//    cell boundary by ~2 u of the piece: at most 4 u length max|g| per sub-piece (the field is
//    continuous, the TF may jump), and with g = C tau never more than 2 C_max T (what any part can add).
//  - the quadrature sums and the running colour sum: 32 u of each term, u of the sum per add.
// Every bound is a sum of non-negative terms evaluated in double; its own rounding is irrelevant.
void ExactRay::integrateSubPiece(double length, const Cubic& s, double a, double b, double sScale,
                                 const WrongSide& wrong, std::size_t below) {
    // Where s may be beyond the segment: the depth from here on is uncertain by wrong.depth more, and the
    // colour by wrong.colour plus what the true emission there, at most C_high tau_high, may see of the
    // depth's uncertainty (the sum of the sub-piece covers the used emission's).
    depthError_ += wrong.depth;
    wholeWindow_ = wholeWindow_ || wrong.whole;
    std::array<double, 3> wrongColour = wrong.colour;
    for (int c = 0; c < 3; ++c) wrongColour[c] += wrong.seen[c] * depthError_;
    // The TF segment the sub-piece lies in: that of the `below` levels <= s at its middle.
    const Gap& gap = gaps_[below];
    if (gap.zero) {
        // Adds exactly nothing and multiplies the transparency by exactly 1, but where s may be beyond
        // the segment the TF may not be zero.
        if (wrong.depth > 0.0 || wrongColour[0] > 0.0 || wrongColour[1] > 0.0 || wrongColour[2] > 0.0) {
            const double front = std::exp(-(opticalDepth_ - depthError_));
            for (int c = 0; c < 3; ++c) roundingError_[c] += front * wrongColour[c];
        }
        return;
    }
    ++subPieces;

    // Everything as polynomials in lambda in [0, 1] over the sub-piece.
    const Cubic local = a == 0.0 && b == 1.0 ? s : s.reparameterised(a, b - a);  // the same bits for a whole piece
    const double ell = length * (b - a);
    const std::size_t segment = gap.segment;
    const SubPiece piece = setUp(local, ell, sScale, segments_[segment], !batch_);
    const double depthErrorInFront = depthError_;
    if (batch_) {
        // The Gauss rules wait for the batch (exact_gauss_batch.h); the depth goes on now, for done().
        GaussBatch& q = *batch_;
        const int j = queued_++;
        for (int k = 0; k < 4; ++k) q.c[k][j] = local.c[k];
        q.ell[j] = ell;
        q.sScale[j] = sScale;
        const Segment& seg = segments_[segment];
        q.segmentS[j] = seg.s;
        for (int k = 0; k < 4; ++k) {
            q.value[k][j] = seg.value[k];
            q.slope[k][j] = seg.slope[k];
        }
        q.depthInFront[j] = opticalDepth_;
        queuedLength_[j] = length;
        queuedDepthError_[j] = depthErrorInFront;
        queuedWrongSide_[j] = wrongColour;
    } else {
        double sum[3] = {}, error[3] = {}, rounding[3] = {};
        const double front = std::exp(-opticalDepth_);
        adaptiveQuadrature(piece, front, sum, error, rounding);
        accumulate(front, depthErrorInFront, sum, error, rounding, piece.gMax, length, wrongColour);
    }
    opticalDepth_ += horner(piece.depth, 1.0);
    depthError_ += piece.depthError + length * 4.0 * kUnit * piece.tau.sum + kUnit * opticalDepth_;
    if (queued_ == GaussBatch::kCapacity) flush();
}

ExactRay::SubPiece ExactRay::setUp(const Cubic& local, double ell, double sScale, const Segment& segment,
                                   bool withColour) const {
    SubPiece r;
    r.local = local;
    r.ell = ell;
    const ScalarDoubleOps o;
    const double ds = segment_kernel::coefficientError(o, sScale);
    // The channels along the sub-piece (segment_kernel.h: the Gauss batch's lanes run the same).
    r.tau = segment_kernel::alongSegment(o, local.c, segment.s, segment.value[0], segment.slope[0], ds);
    const segment_kernel::Depth<double> depth = segment_kernel::depthAlong(o, r.tau, ell);
    r.depth = depth.p;
    r.depthError = depth.error;
    if (!withColour) return r;
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    for (int c = 0; c < 3; ++c) {
        r.colour[c] = segment_kernel::alongSegment(o, local.c, segment.s, segment.value[c + 1], segment.slope[c + 1], ds);
        segment_kernel::emissionBounds(o, r.colour[c], r.tau, colourTimesExtinction, r.gMax[c], r.gError[c]);
    }
    return r;
}

void ExactRay::flush() {
    if (queued_ == 0) return;
    const GaussBatch& q = *batch_;
    integrateGaussBatch(*batch_, queued_, tolerance_, emission_ == EmissionModel::ColourTimesExtinction);
    for (int j = 0; j < queued_; ++j) {
        if (q.panels[j] > 0) {
            quadratureIntervals += q.panels[j];
            quadratureNodes += q.nodes[j];
            const double sum[3] = {q.sum[0][j], q.sum[1][j], q.sum[2][j]};
            const double error[3] = {q.error[0][j], q.error[1][j], q.error[2][j]};
            const double rounding[3] = {q.rounding[0][j], q.rounding[1][j], q.rounding[2][j]};
            const double gMax[3] = {q.gMax[0][j], q.gMax[1][j], q.gMax[2][j]};
            accumulate(q.front[j], queuedDepthError_[j], sum, error, rounding, gMax, queuedLength_[j], queuedWrongSide_[j]);
        } else {  // no Gauss rule within reach
            const Cubic local{{q.c[0][j], q.c[1][j], q.c[2][j], q.c[3][j]}};
            const Segment segment{q.segmentS[j],
                                  {q.value[0][j], q.value[1][j], q.value[2][j], q.value[3][j]},
                                  {q.slope[0][j], q.slope[1][j], q.slope[2][j], q.slope[3][j]}};
            const SubPiece piece = setUp(local, q.ell[j], q.sScale[j], segment, true);
            double sum[3] = {}, error[3] = {}, rounding[3] = {};
            adaptiveQuadrature(piece, q.front[j], sum, error, rounding);
            accumulate(q.front[j], queuedDepthError_[j], sum, error, rounding, piece.gMax, queuedLength_[j],
                       queuedWrongSide_[j]);
        }
    }
    queued_ = 0;
}

// The sums are in units of the transparency in front of the sub-piece, `front`: adaptive quadrature on
// [0, 1], all channels together (they share the transparency).
void ExactRay::adaptiveQuadrature(const SubPiece& piece, double front, double sum[3], double error[3],
                                  double rounding[3]) {
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    const Linear& tau = piece.tau;
    const Linear(&colour)[3] = piece.colour;
    const std::array<double, 5>& depth = piece.depth;
    const double ell = piece.ell, depthError = piece.depthError;
    const double* gError = piece.gError;
    const std::array<double, 4> colours[3] = {colour[0].p, colour[1].p, colour[2].p};
    struct Interval {
        double x0, x1;
        int depth;
    };
    Interval stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = {0.0, 1.0, 0};
    // C and tau are linear in s: on an interval their extremes lie where s's do, at its ends or where
    // s' = 0 (a sub-piece is split at TF points only, so s need not be monotone on it).
    double critical[2];
    int criticals = -1;  // found when an enclosure first needs them
    auto range = [&](const Linear& f, double x0, double x1, double& lo, double& hi) {
        if (criticals < 0) criticals = criticalPoints(piece.local, 0.0, 1.0, critical);
        const double at0 = horner(f.p, x0), at1 = horner(f.p, x1);
        lo = std::min(at0, at1);
        hi = std::max(at0, at1);
        for (int i = 0; i < criticals; ++i)
            if (critical[i] > x0 && critical[i] < x1) {
                const double v = horner(f.p, critical[i]);
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        lo -= f.error;
        hi += f.error;
    };
    for (int intervals = 1; top > 0; ++intervals) {
        const Interval iv = stack[--top];
        ++quadratureIntervals;
        const double width = iv.x1 - iv.x0;
        const bool last = iv.depth >= kMaxDepth || intervals >= kMaxIntervals;
        const double d0 = horner(depth, iv.x0), d1 = horner(depth, iv.x1);
        const double dd0 = iv.x0 * depthError, dd1 = iv.x1 * depthError;
        // The depth grows along the interval: the transparency on it is at most tHigh. The exact depth
        // never falls (tau >= 0), so no transparency after the sub-piece's start exceeds 1, whatever the
        // depth's error (a huge one made exp(-(d0 - dd0)) inf, and 0 times it NaN).
        const double tHigh = iv.x0 == 0.0 ? 1.0 : std::min(1.0, std::exp(-(d0 - dd0)));
        if (d1 - d0 <= kResolvedDepth) {
            double K[3], G[3], e[3], worst = 0.0;
            if (lowOrder_)
                applyRule(kKronrod7, iv.x0, iv.x1, depth, tau.p, colours, colourTimesExtinction, K, G);
            else
                applyRule(kKronrod15, iv.x0, iv.x1, depth, tau.p, colours, colourTimesExtinction, K, G);
            quadratureNodes += lowOrder_ ? 7 : 15;
            for (int c = 0; c < 3; ++c) {
                e[c] = ell * 0.5 * width * std::abs(K[c] - G[c]);
                worst = std::max(worst, e[c]);
            }
            if (front * worst <= tolerance_ * width || last) {
                for (int c = 0; c < 3; ++c) {
                    const double value = ell * 0.5 * width * K[c];
                    sum[c] += value;
                    error[c] += e[c];
                    rounding[c] += ell * width * tHigh * gError[c] + (std::abs(value) + e[c]) * (dd1 + 32.0 * kUnit);
                }
                continue;
            }
        } else {
            double cLow[3], cHigh[3];
            for (int c = 0; c < 3; ++c) range(colour[c], iv.x0, iv.x1, cLow[c], cHigh[c]);
            const double tLow0 = std::exp(-(d0 + dd0)), tHigh1 = std::min(1.0, std::exp(-(d1 - dd1))),
                         tLow1 = std::exp(-(d1 + dd1));
            const double fLow = colourTimesExtinction ? std::max(0.0, tLow0 - tHigh1) : ell * width * tLow1;
            const double fHigh = colourTimesExtinction ? tHigh - tLow1 : ell * width * tHigh;
            double lo[3], hi[3], worst = 0.0;
            for (int c = 0; c < 3; ++c) {
                lo[c] = std::min(cLow[c] * fLow, cLow[c] * fHigh);
                hi[c] = std::max(cHigh[c] * fHigh, cHigh[c] * fLow);
                worst = std::max(worst, 0.5 * (hi[c] - lo[c]));
            }
            if (front * worst <= tolerance_ * width || last) {
                for (int c = 0; c < 3; ++c) {
                    const double value = 0.5 * (lo[c] + hi[c]), e = 0.5 * (hi[c] - lo[c]);
                    sum[c] += value;
                    error[c] += e;
                    rounding[c] += (std::abs(value) + e) * 8.0 * kUnit;
                }
                continue;
            }
        }
        const double centre = 0.5 * (iv.x0 + iv.x1);
        stack[top++] = {centre, iv.x1, iv.depth + 1};
        stack[top++] = {iv.x0, centre, iv.depth + 1};
    }
}

void ExactRay::accumulate(double front, double depthErrorInFront, const double sum[3], const double error[3],
                          const double rounding[3], const double gMax[3], double length,
                          const std::array<double, 3>& wrong) {
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    const double frontError = depthErrorInFront + 2.0 * kUnit;  // relative, of `front`
    for (int c = 0; c < 3; ++c) {
        colour_[c] += front * sum[c];
        quadratureError_[c] += front * error[c];
        const double sliver = std::min(4.0 * kUnit * length * gMax[c] + wrong[c],
                                       colourTimesExtinction ? 2.0 * maxColour_[c] : gMax[c] * length + wrong[c]);
        roundingError_[c] += front * (rounding[c] + (std::abs(sum[c]) + error[c]) * frontError + sliver) +
                             kUnit * std::abs(colour_[c]);
    }
}

void ExactRay::finish(double remainingLength, double value[4], double bound[4]) {
    flush();
    const double transparencyHigh = std::exp(-(opticalDepth_ - depthError_));  // at least the exact T
    const bool cut = remainingLength > 0.0;
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    for (int c = 0; c < 3; ++c) {
        value[c] = colour_[c];
        // What the part after the cut could have added: at most C_max (T_cut - T_end) for g = C tau,
        // at most C_max T_cut times the length for g = C.
        const double tail = cut ? transparencyHigh * maxColour_[c] * (colourTimesExtinction ? 1.0 : remainingLength)
                                : 0.0;
        bound[c] = quadratureError_[c] + roundingError_[c] + tail;
        // The exact colour lies in [0, C_max] with g = C tau, in [0, C_max L] with g = C (T <= 1; L the
        // length of the pieces walked and cut off, the ray's only parts where g may be non-zero) whatever
        // the extinction: a bound never needs to exceed the distance to the farther end (this also
        // replaces an overflowed one).
        const double most = maxColour_[c] * (colourTimesExtinction ? 1.0 : lengthWalked_ + remainingLength);
        const double widest = std::max(std::abs(value[c]), std::abs(most - value[c]));
        if (!(bound[c] <= widest)) bound[c] = widest;
    }
    value[3] = -std::expm1(-opticalDepth_);  // 1 - T, accurate for thin media too
    bound[3] = transparencyHigh * depthError_ + kUnit * value[3] + (cut ? transparencyHigh : 0.0);
    const double widest = std::max(value[3], 1.0 - value[3]);  // alpha lies in [0, 1]
    if (!(bound[3] <= widest)) bound[3] = widest;
}

}  // namespace vri
