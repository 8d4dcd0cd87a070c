#pragma once
// The emission-absorption integral along one ray whose scalar is a cubic on each piece, solved to
// near double precision with a bound on its error (see exact_reference.h for the method).
#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "libvri/core/constant_face.h"
#include "libvri/core/cubic.h"
#include "libvri/core/exact_gauss_batch.h"
#include "libvri/core/exact_piece_batch.h"
#include "libvri/core/segment_kernel.h"  // outside any Highway target region: included once
#include "libvri/core/transfer_function.h"

namespace vri {

class ExactRay {
public:
    // From this tolerance up a sub-piece first tries the cheapest Gauss rule with a derivative bound
    // (exact_gauss_batch.h; up to 64 panels, batched over SIMD lanes), and only where none reaches the
    // tolerance the adaptive Gauss-Kronrod quadrature. Below it (vri-reference's 1e-13) only the adaptive
    // quadrature runs: the references, and every result compared against them, keep their bits.
    static constexpr double kGaussTolerance = 1e-10;

    // Allocates all the scratch space a ray needs: the per-ray calls allocate nothing. `tolerance`
    // is the error allowed per transfer-function sub-piece (in the pixel's units); it also chooses
    // the quadrature rule and where a ray may end early (see done()).
    ExactRay(const TransferFunction& tf, double tolerance);

    void begin();  // starts a new ray
    // The next piece, front to back: `length` world units over which s = cubic(sigma), sigma in
    // [0, 1] from the piece's start to its end. `sScale` bounds the magnitudes whose rounding went
    // into the cubic's coefficients (see the error analysis in exact_ray.cpp). `exact`: the cubic is the
    // model's scalar itself, a constant, as on a cell whose eight corners hold one value (the corners'
    // scalars are the model's, exact_reference.h): no rounding puts it on the wrong side of a TF point,
    // and one at its value counts from that value on (right-continuous), as every method reads the TF.
    // `cell`: the cell the piece crosses, where the walk knows it: where s comes within rounding of a TF
    // point, a face of the cell whose corners hold that point's value tells s's side of it (constant_face.h).
    struct PieceCell {
        const PieceBatch& batch;  // the piece's corners (raw values) and weights, lane `lane`
        int lane;
        double lo, invRange;  // the model's map from raw values to s (exact_reference.h)
    };
    void addPiece(double length, const Cubic& s, double sScale, bool exact, const PieceCell* cell = nullptr);
    // True once what the rest of the ray, `remainingLength` world units, could still add is at most
    // the tolerance in every channel: the transparency T times the largest colour (g = C tau adds at
    // most C_max T; g = C at most C_max T times the length), and T to alpha. finish() adds that to the
    // bound. Also true once T < 2^-60, where a cut changes alpha by nothing in double.
    // Inline: the walk asks after every piece, and most of the time the first two tests answer.
    bool done(double remainingLength) const {
        if (opticalDepth_ >= kOpaqueDepth) return true;
        // The tests use the largest transparency the rounding of the depth allows, as finish() does.
        const double depth = opticalDepth_ - depthError_;
        return depth >= terminationDepth_ && doneAtDepth(depth, remainingLength);
    }
    // Ends the ray, `remainingLength` world units of which were left out after done(): RGBA and
    // a bound on each channel's error.
    void finish(double remainingLength, double value[4], double bound[4]);
    // The optical depth of the ray so far, complete once finish() has run (pre-integration tabulates it).
    double opticalDepth() const { return opticalDepth_; }

    // Whether the TF is zero on all of [s0, s1]: tf.isInvisible(s0, s1) from a table of the spans where
    // it is zero, not a search (true only where that is; an ulp short of a jump out of zero).
    bool invisible(double s0, double s1) const;

    std::uint64_t subPieces = 0, quadratureIntervals = 0, quadratureNodes = 0;  // counted over all rays
    // Whether this ray (since begin()) had a sub-piece bounded as if all of it might lie beyond its TF
    // segment: s within rounding of a TF point all along it as far as the window analysis could show
    // (nearly tangent to the level, constant on it but not known exactly, a critical point on it, or a
    // sub-piece shorter than the window). Where many rays did, their bounds may be loose there.
    bool wholeSubPieceWindow() const { return wholeWindow_; }

private:
    static constexpr double kOpaqueDepth = 41.588830833596716;  // 60 ln 2

    // A transfer-function segment: from s on, channel k (tau, R, G, B) is value[k] + slope[k] (s' - s).
    struct Segment {
        double s;
        std::array<double, 4> value, slope;
    };
    // A channel along a sub-piece: v + m (s - segment.s) as a cubic in lambda (segment_kernel.h).
    using Linear = segment_kernel::Linear<double>;
    // What the quadrature of one sub-piece needs, as polynomials in lambda in [0, 1].
    struct SubPiece {
        Cubic local;
        double ell;
        Linear tau, colour[3];
        double gMax[3], gError[3];    // bounds on the emission g and on its error where a rule evaluates it
        std::array<double, 5> depth;  // the optical depth from the sub-piece's start
        double depthError;            // bound on the depth's error at lambda = 1 (lambda times it at lambda)
    };

    // What a split at TF level i can change where rounding puts s on its wrong side (exact_ray.cpp):
    // per channel (tau, R, G, B) the jump across the level, the steeper slope of the two segments
    // beside it and the larger value at it; `gap` the distance to the nearest other level.
    struct LevelStep {
        std::array<double, 4> jump, slope, high;
        double gap;
    };
    // Per sub-piece, in units of the transparency in front of it: the optical depth and the colour that
    // the parts of it where s may lie beyond its segment can change (exact_ray.cpp, "wrong side").
    struct WrongSide {
        double depth = 0.0;
        std::array<double, 3> colour{};
        std::array<double, 3> seen{};  // the width times the TF's largest emission there
        bool whole = false;            // the whole sub-piece counted
    };

    // Gap g of the levels, level g - 1 <= s < level g (gap 0 below the first, the last from the last on):
    // the TF segment there.
    struct Gap {
        std::size_t segment;  // into segments_
        bool zero;            // the TF is zero on it: a sub-piece there adds nothing
    };

    bool doneAtDepth(double depth, double remainingLength) const;  // done() past terminationDepth_
    // How far the computed s may be from the exact one (exact_ray.cpp, "wrong side").
    static double wrongSideEps(double sScale);
    // `below`: the levels <= s at the sub-piece's middle.
    WrongSide wrongSide(double length, const Cubic& s, double a, double b, double sScale, int parts,
                        const double* ends, std::size_t below) const;
    // The window from the sub-piece's end `at` towards `into` where s may be beyond `level`; s is monotone from
    // `at` to `monotoneTo` (the nearest critical point inside, or `into`).
    double wrongSideWidth(const Cubic& s, double at, double sAt, double into, double monotoneTo, double level,
                          bool above, double eps) const;
    // The window from `at` towards `into` (within the piece) where s may be beyond `level`, as the piece's
    // constant faces at the level show it; |into - at| where none shows one.
    double faceWidth(double level, double at, double into, bool above, double eps) const;
    // What `span` world units beside level i where s may be on its other side add to `r`.
    void addWindow(WrongSide& r, double span, std::size_t level, double eps) const;
    void integrateSubPiece(double length, const Cubic& s, double a, double b, double sScale, const WrongSide& wrong,
                           std::size_t below);
    SubPiece setUp(const Cubic& local, double ell, double sScale, const Segment& segment, bool withColour) const;
    void adaptiveQuadrature(const SubPiece& piece, double front, double sum[3], double error[3], double rounding[3]);
    void accumulate(double front, double depthErrorInFront, const double sum[3], const double error[3],
                    const double rounding[3], const double gMax[3], double length, const std::array<double, 3>& wrong);
    void flush();  // integrates the queued sub-pieces, in order

    const TransferFunction& tf_;
    EmissionModel emission_;
    double tolerance_;
    bool lowOrder_;                // Gauss-Kronrod 3-7 instead of 7-15 (see integrateSubPiece)
    bool fastSplits_;              // a piece's monotonicity from its coefficients where they show it (addPiece)
    RootStart rootStart_;          // Chord with fastSplits_: the same roots to an ulp, fewer Newton steps
    double terminationDepth_;      // g = C tau: done() once the optical depth reaches this
    double largestColour_;         // max(1, C_max over channels): what bounds a tail per unit T
    std::vector<double> levels_;   // the distinct s of the TF points: where a piece is split
    std::vector<LevelStep> steps_;  // per level
    std::vector<Gap> gaps_;         // per gap: levels_.size() + 1
    std::array<double, 4> channelMax_{};  // the largest tau, R, G, B of the TF
    std::vector<double> splits_;   // scratch: a piece's split points in sigma
    ConstantFace faces_[6];        // scratch: the faces of the piece's cell whose corners hold one scalar
    int faceCount_ = 0;
    std::vector<std::pair<double, double>> invisibleSpans_;  // closed spans of s where the TF is zero
    // Segment i < n - 1 runs from point i to point i + 1; n - 1 and n are the constants below the first
    // point and above the last (n points).
    std::vector<Segment> segments_;
    std::array<double, 3> maxColour_{};

    // The ray so far.
    double opticalDepth_ = 0.0, depthError_ = 0.0;
    double lengthWalked_ = 0.0;  // of the pieces given to addPiece: the rest of the ray's segment has g = 0
    std::array<double, 3> colour_{}, quadratureError_{}, roundingError_{};
    bool wholeWindow_ = false;  // see wholeSubPieceWindow()

    // From kGaussTolerance up: the sub-pieces waiting for their Gauss rules, with what the ray needs of
    // each once they are done (the optical depth has already moved past them).
    std::unique_ptr<GaussBatch> batch_;
    int queued_ = 0;
    std::array<double, GaussBatch::kCapacity> queuedLength_, queuedDepthError_;
    std::array<std::array<double, 3>, GaussBatch::kCapacity> queuedWrongSide_;
};

}  // namespace vri
