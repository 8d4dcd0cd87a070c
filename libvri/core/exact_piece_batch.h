#pragma once
// The cubics of the exact method's pieces (exact_reference.cpp) formed many at once. The walk of one ray
// queues each visible piece here, structure of arrays: its cell's corner values and base index and
// where it starts and ends on the ray. Highway vectors of doubles then form, one piece per lane, the
// trilinear weights at its ends, the cubic of s along it and its sScale (exact_ray.h), with the walk's
// scalar formulas in the same order, unfused, so every bit is the same on every Highway target and as
// one piece at a time. The pieces go on to the ray in walk order; only this arithmetic is batched.

namespace vri {

// What is fixed along one ray: its voxel-index coordinates entry + phi delta, phi in [0, 1]; per axis the
// largest coordinate and whether the axis has more than one voxel (a single layer has weight 0); and the
// map from raw values to s, (raw - lo) invRange.
struct PieceFrame {
    double entry[3], delta[3], maxCoord[3];
    bool varies[3];
    double lo, invRange;
};

struct PieceBatch {
    static constexpr int kCapacity = 16;  // a multiple of the widest target's lanes (8 doubles)

    // Filled by the walk, per piece: the cell's corners (dx, dy, dz) = k & 1, k >> 1 & 1, k >> 2 as raw
    // values; the cell's base index per axis; the piece's ends on the ray; max(|min corner|, |max corner|).
    alignas(64) double corner[8][kCapacity];
    alignas(64) double cell[3][kCapacity];
    alignas(64) double phiA[kCapacity], phiB[kCapacity];
    alignas(64) double magnitude[kCapacity];

    // Results: s(sigma) = c[0] + c[1] sigma + c[2] sigma^2 + c[3] sigma^3 for sigma in [0, 1] along the
    // piece, and the sScale that bounds the magnitudes whose rounding went into it.
    alignas(64) double c[4][kCapacity];
    alignas(64) double sScale[kCapacity];
    // The cell weights at the piece's ends, per axis: the cubic runs from w0 to w1 as trilinearAlongSegment's.
    alignas(64) double w0[3][kCapacity], w1[3][kCapacity];
    // 1 where the cubic is the model's scalar exactly (exact_reference.h): every corner that weighs on the
    // piece holds one value v, and the cubic came out as the constant (v - lo) * r with no rounding; else 0.
    alignas(64) double exact[kCapacity];
};

// Forms the cubics of pieces [0, count); entries from count up to the next whole vector are overwritten
// with a harmless piece first.
void formPieceCubics(PieceBatch& batch, int count, const PieceFrame& frame);

}  // namespace vri
