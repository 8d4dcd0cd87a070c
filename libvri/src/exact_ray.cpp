#include "exact_ray.h"

#include <algorithm>
#include <cmath>

namespace vri {

namespace {

// Gauss-Kronrod 7-15 on [-1, 1] (QUADPACK's qk15): the Kronrod nodes are +-kNode[i], i < 7, and
// kNode[7] = 0; the Gauss nodes are kNode[1], kNode[3], kNode[5] (+-) and 0.
constexpr double kNode[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                             0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                             0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                             0.207784955007898467600689403773245, 0.0};
constexpr double kKronrod[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kGauss[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                              0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
constexpr int kMaxDepth = 40;  // bisections of one sub-piece; reached only by pathological input
constexpr double kUnit = 0x1p-53;  // unit roundoff u of double

template <std::size_t N>
double horner(const std::array<double, N>& p, double x) {
    double r = p[N - 1];
    for (std::size_t k = N - 1; k-- > 0;) r = r * x + p[k];
    return r;
}

template <std::size_t N>
double absSum(const std::array<double, N>& p) {
    double r = 0.0;
    for (double v : p) r += std::abs(v);
    return r;
}

}  // namespace

ExactRay::ExactRay(const TransferFunction& tf, double tolerance)
    : tf_(tf), emission_(tf.emission()), tolerance_(tolerance) {
    for (const auto& p : tf.points()) {
        pointS_.push_back(p.s);
        if (levels_.empty() || levels_.back() != p.s) levels_.push_back(p.s);
        maxColour_ = {std::max(maxColour_[0], p.r), std::max(maxColour_[1], p.g), std::max(maxColour_[2], p.b)};
    }
    // Each of a piece's at most three monotone parts crosses each level at most once.
    splits_.reserve(3 * levels_.size() + 2);
}

void ExactRay::begin() {
    opticalDepth_ = depthError_ = 0.0;
    colour_ = quadratureError_ = roundingError_ = {};
}

void ExactRay::addPiece(double length, const Cubic& s, double sScale) {
    if (!(length > 0.0)) return;
    double ends[4] = {0.0}, values[4];
    double critical[2];
    const int nc = criticalPoints(s, 0.0, 1.0, critical);
    for (int i = 0; i < nc; ++i) ends[i + 1] = critical[i];
    ends[nc + 1] = 1.0;
    const int parts = nc + 1;
    for (int i = 0; i <= parts; ++i) values[i] = s(ends[i]);
    const auto [lo, hi] = std::minmax_element(values, values + parts + 1);
    if (tf_.isInvisible(*lo, *hi)) return;  // neither extinction nor emission anywhere on the piece

    // Split where s crosses a transfer-function point: within a monotone part at most once per level,
    // in the order of the levels when s rises and in reverse when it falls.
    splits_.clear();
    splits_.push_back(0.0);
    for (int i = 0; i < parts; ++i) {
        const double a = ends[i], b = ends[i + 1], sa = values[i], sb = values[i + 1];
        const auto first = std::upper_bound(levels_.begin(), levels_.end(), std::min(sa, sb));
        const auto last = std::lower_bound(first, levels_.end(), std::max(sa, sb));
        auto split = [&](double level) { splits_.push_back(std::max(solveMonotone(s, level, a, b), splits_.back())); };
        if (sa < sb)
            for (auto it = first; it != last; ++it) split(*it);
        else
            for (auto it = last; it != first;) split(*--it);
    }
    splits_.push_back(1.0);
    for (std::size_t i = 0; i + 1 < splits_.size(); ++i)
        if (splits_[i + 1] > splits_[i]) integrateSubPiece(length, s, splits_[i], splits_[i + 1], sScale);
}

// Error analysis. The result is exact for the model (trilinear field, piecewise-linear TF, along the
// ray as computed) up to (1) the quadrature, whose error per interval is estimated by |K15 - G7| (an
// overestimate: K15 is far more accurate than G7), and (2) rounding, bounded with u = 2^-53 as follows,
// the constants being generous counts of the operations involved:
//  - s: its cubic comes from the corner values through three lerps, the normalisation and the Taylor
//    shift; each coefficient carries at most ~20 roundings of terms below sScale: |ds| <= 32 u sScale.
//  - tau, C (cubics in the sub-piece variable): forming v_A + m (s - s_A) and evaluating by Horner
//    adds <= 16 u (sum|coefficients| + |v_A| + |m s_A|); the error of s enters times the TF slope |m|.
//  - g = C tau (or C): the product of two such cubics, <= dC |tau| + |C| dtau + 16 u |C| |tau|.
//  - optical depth: the quartic integral of tau, error <= length (dtau + 8 u sum|tau|) per sub-piece,
//    plus u times the running sum per addition; the transparency exp(-depth) in front of a sub-piece
//    then has relative error <= depthError + 2 u, and so has every contribution behind it.
//  - a split misplaced by rounding (a root to within an ulp, a cell face) moves the TF segment or the
//    cell boundary by ~2 u of the piece: at most 4 u length max|g| per sub-piece (the field is
//    continuous, the TF may jump).
//  - the 15-term quadrature sums and the running colour sum: 32 u of each term, u of the sum per add.
// Every bound is a sum of non-negative terms evaluated in double; its own rounding is irrelevant.
void ExactRay::integrateSubPiece(double length, const Cubic& s, double a, double b, double sScale) {
    // The TF segment [A, B] the sub-piece lies in (constant beyond the ends; right-continuous at jumps).
    const auto& points = tf_.points();
    const double sMid = s(0.5 * (a + b));
    std::size_t iA = 0, iB = 0;
    if (!(sMid < pointS_.front())) {
        if (!(sMid < pointS_.back())) {
            iA = iB = points.size() - 1;
        } else {
            iA = static_cast<std::size_t>(std::upper_bound(pointS_.begin(), pointS_.end(), sMid) - pointS_.begin()) - 1;
            iB = iA + 1;
        }
    }
    const TransferFunctionPoint& A = points[iA];
    const TransferFunctionPoint& B = points[iB];
    const bool colourTimesExtinction = emission_ == EmissionModel::ColourTimesExtinction;
    if (A.tau == 0.0 && B.tau == 0.0 &&
        (colourTimesExtinction || (A.r == 0.0 && A.g == 0.0 && A.b == 0.0 && B.r == 0.0 && B.g == 0.0 && B.b == 0.0)))
        return;  // adds exactly nothing and multiplies the transparency by exactly 1
    ++subPieces;

    // Everything as polynomials in lambda in [0, 1] over the sub-piece.
    const Cubic local = s.reparameterised(a, b - a);
    const double ell = length * (b - a);
    const double inverseWidth = iA == iB ? 0.0 : 1.0 / (B.s - A.s);
    const double ds = 32.0 * kUnit * sScale;
    struct Linear {
        std::array<double, 4> p;
        double error;  // bound on |computed - exact| anywhere on [0, 1]
    };
    auto alongSegment = [&](double vA, double vB) {
        const double m = (vB - vA) * inverseWidth;
        Linear r{{vA + m * (local.c[0] - A.s), m * local.c[1], m * local.c[2], m * local.c[3]}, 0.0};
        r.error = 16.0 * kUnit * (absSum(r.p) + std::abs(vA) + std::abs(m * A.s)) + std::abs(m) * ds;
        return r;
    };
    const Linear tau = alongSegment(A.tau, B.tau);
    const Linear colour[3] = {alongSegment(A.r, B.r), alongSegment(A.g, B.g), alongSegment(A.b, B.b)};
    const double tauSum = absSum(tau.p);

    std::array<double, 7> g[3];  // the emission of each channel
    double gMax[3], gError[3];
    for (int c = 0; c < 3; ++c) {
        g[c] = {};
        const double colourSum = absSum(colour[c].p);
        if (colourTimesExtinction) {
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) g[c][i + j] += colour[c].p[i] * tau.p[j];
            gMax[c] = colourSum * tauSum;
            gError[c] = colour[c].error * tauSum + colourSum * tau.error + 16.0 * kUnit * gMax[c];
        } else {
            for (int i = 0; i < 4; ++i) g[c][i] = colour[c].p[i];
            gMax[c] = colourSum;
            gError[c] = colour[c].error;
        }
    }
    std::array<double, 5> depth{};  // optical depth from the sub-piece's start: ell * integral of tau
    for (int k = 0; k < 4; ++k) depth[k + 1] = ell * tau.p[k] / (k + 1);

    // Adaptive Gauss-Kronrod on [0, 1], all channels together (they share the transparency).
    const double front = std::exp(-opticalDepth_);
    const double weight = front * ell;  // turns an integral over lambda into the pixel's units
    struct Interval {
        double x0, x1;
        int depth;
    };
    Interval stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = {0.0, 1.0, 0};
    double sum[3] = {};
    while (top > 0) {
        const Interval iv = stack[--top];
        ++quadratureIntervals;
        const double half = 0.5 * (iv.x1 - iv.x0), centre = 0.5 * (iv.x0 + iv.x1);
        double kronrod[3] = {}, gauss[3] = {};
        auto add = [&](double x, int i) {
            const double t = std::exp(-horner(depth, x));
            for (int c = 0; c < 3; ++c) {
                const double f = horner(g[c], x) * t;
                kronrod[c] += kKronrod[i] * f;
                if (i % 2 == 1) gauss[c] += kGauss[i / 2] * f;
            }
        };
        for (int i = 0; i < 7; ++i) {
            add(centre - half * kNode[i], i);
            add(centre + half * kNode[i], i);
        }
        const double tc = std::exp(-horner(depth, centre));
        for (int c = 0; c < 3; ++c) {
            const double f = horner(g[c], centre) * tc;
            kronrod[c] += kKronrod[7] * f;
            gauss[c] += kGauss[3] * f;
        }
        double error[3], worst = 0.0;
        for (int c = 0; c < 3; ++c) {
            error[c] = weight * half * std::abs(kronrod[c] - gauss[c]);
            worst = std::max(worst, error[c]);
        }
        if (worst <= tolerance_ * (iv.x1 - iv.x0) || iv.depth >= kMaxDepth) {
            for (int c = 0; c < 3; ++c) {
                sum[c] += half * kronrod[c];
                quadratureError_[c] += error[c];
            }
        } else {
            stack[top++] = {centre, iv.x1, iv.depth + 1};
            stack[top++] = {iv.x0, centre, iv.depth + 1};
        }
    }

    const double depthAcross = horner(depth, 1.0);
    const double depthError = ell * (tau.error + 8.0 * kUnit * tauSum);
    const double frontError = depthError_ + 2.0 * kUnit;  // relative, of `front`
    for (int c = 0; c < 3; ++c) {
        colour_[c] += weight * sum[c];
        roundingError_[c] += weight * (gError[c] + gMax[c] * (frontError + depthError + kUnit * depthAcross + 32.0 * kUnit)) +
                             front * length * 4.0 * kUnit * gMax[c] + kUnit * colour_[c];
    }
    opticalDepth_ += depthAcross;
    depthError_ += depthError + length * 4.0 * kUnit * tauSum + kUnit * opticalDepth_;
}

void ExactRay::finish(double remainingLength, double value[4], double bound[4]) const {
    const double transparency = std::exp(-opticalDepth_);
    const bool cut = remainingLength > 0.0;
    for (int c = 0; c < 3; ++c) {
        value[c] = colour_[c];
        // What the part after the cut could have added: at most C_max (T_cut - T_end) for g = C tau,
        // at most C_max T_cut times the length for g = C.
        const double tail = cut ? transparency * maxColour_[c] *
                                      (emission_ == EmissionModel::ColourTimesExtinction ? 1.0 : remainingLength)
                                : 0.0;
        bound[c] = quadratureError_[c] + roundingError_[c] + tail;
    }
    value[3] = -std::expm1(-opticalDepth_);  // 1 - T, accurate for thin media too
    bound[3] = transparency * depthError_ + kUnit * value[3] + (cut ? transparency : 0.0);
}

}  // namespace vri
