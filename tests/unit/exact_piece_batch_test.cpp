// The exact method's batched cubics (exact_piece_batch.h) against the formulas of one piece at a time:
// the walk's clamped weights, cubic.h's trilinearAlongSegment and the normalisation to s, bit for bit on
// every Highway target this CPU and build have.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <hwy/targets.h>

#include "libvri/core/cubic.h"
#include "libvri/core/exact_piece_batch.h"

namespace {

using vri::PieceBatch;
using vri::PieceFrame;

struct Piece {
    std::array<double, 8> corner;
    int cell[3];
    double phiA, phiB;
};

// One piece as the walk formed it before the batch (exact_reference.cpp's GridWalker): the specification.
// `exact`: the corners that weigh on the piece (along an axis the ray does not move along, a weight of 0
// leaves out the far corners and 1 the near ones) hold one value, and the cubic is that value's scalar.
void onePiece(const Piece& p, const PieceFrame& f, double c[4], double& sScale, bool& exact, glm::dvec3& w0,
              glm::dvec3& w1) {
    w0 = w1 = glm::dvec3(0.0);
    for (int a = 0; a < 3; ++a) {
        auto weight = [&](double phi) {
            return std::clamp(std::clamp(f.entry[a] + phi * f.delta[a], 0.0, f.maxCoord[a]) - p.cell[a], 0.0, 1.0);
        };
        if (f.varies[a]) w0[a] = weight(p.phiA), w1[a] = weight(p.phiB);
    }
    const vri::Cubic raw = vri::trilinearAlongSegment(p.corner, w0, w1);
    c[0] = (raw.c[0] - f.lo) * f.invRange;
    for (int k = 1; k < 4; ++k) c[k] = raw.c[k] * f.invRange;
    const auto [lowest, highest] = std::minmax_element(p.corner.begin(), p.corner.end());
    const double magnitude = std::max(std::abs(*lowest), std::abs(*highest));
    sScale = std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]) + (magnitude + std::abs(f.lo)) * f.invRange;
    std::vector<double> weighing;
    for (int k = 0; k < 8; ++k) {
        bool weighs = true;
        for (int a = 0; a < 3; ++a)
            if ((!f.varies[a] || f.delta[a] == 0.0) && w0[a] == ((k >> a & 1) ? 0.0 : 1.0)) weighs = false;
        if (weighs) weighing.push_back(p.corner[k]);
    }
    exact = std::all_of(weighing.begin(), weighing.end(), [&](double v) { return v == weighing.front(); }) &&
            c[0] == (weighing.front() - f.lo) * f.invRange && c[1] == 0.0 && c[2] == 0.0 && c[3] == 0.0;
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

}  // namespace

TEST_CASE("exact piece batch: every target forms the cubics of one piece at a time, bit for bit") {
    std::mt19937_64 random(20261203);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    REQUIRE(!targets.empty());
    for (int frameIndex = 0; frameIndex < 40; ++frameIndex) {
        // Rays in every direction, some along an axis (delta 0) or through a single layer (varies false);
        // raw values of 8 bits, or floats of either sign with zeros of both signs.
        PieceFrame f{};
        for (int a = 0; a < 3; ++a) {
            f.maxCoord[a] = 15.0;
            f.varies[a] = frameIndex % 7 != a;
            f.entry[a] = -1.0 + 18.0 * unit(random);
            f.delta[a] = frameIndex % 5 == a ? 0.0 : -20.0 + 40.0 * unit(random);
            if (f.delta[a] == 0.0) f.entry[a] = std::floor(std::clamp(f.entry[a], 0.0, 13.0));  // on a grid plane
        }
        int fixedAxes = 0;  // bit a: the ray does not move along axis a
        for (int a = 0; a < 3; ++a) fixedAxes |= (!f.varies[a] || f.delta[a] == 0.0) << a;
        const bool floats = frameIndex % 2 == 1;
        f.lo = floats ? -3.0 : 0.0;
        f.invRange = floats ? 1.0 / 7.0 : 1.0 / 255.0;
        std::vector<Piece> pieces;
        for (int i = 0; i < 37; ++i) {  // two full batches and a partial one
            Piece p{};
            for (double& v : p.corner)
                v = floats ? (unit(random) < 0.1 ? (unit(random) < 0.5 ? -0.0 : 0.0) : -4.0 + 8.0 * unit(random))
                           : std::floor(256.0 * unit(random));
            if (i % 4 == 0) std::fill(p.corner.begin() + 1, p.corner.end(), p.corner[0]);  // a constant cell
            if (i % 4 == 1)  // one value on the corners near the fixed axes' grid planes, where their weight is 0
                for (int k = 1; k < 8; ++k)
                    if ((k & fixedAxes) == 0) p.corner[k] = p.corner[0];
            for (int a = 0; a < 3; ++a) p.cell[a] = static_cast<int>(14.0 * unit(random));
            // Along an axis the ray does not move along, the entry on a grid plane: the piece's cell there,
            // its weight 0.
            for (int a = 0; a < 3; ++a)
                if (i % 4 == 1 && f.delta[a] == 0.0) p.cell[a] = static_cast<int>(f.entry[a]);
            // Ends inside [0, 1], at its ends, and beyond the cell (the weights clamp).
            p.phiA = i % 9 == 0 ? 0.0 : unit(random);
            p.phiB = i % 11 == 0 ? 1.0 : std::min(1.0, p.phiA + 0.3 * unit(random));
            pieces.push_back(p);
        }
        using PieceBits = std::array<std::uint64_t, 12>;  // c, sScale, exact, w0, w1
        std::vector<PieceBits> expected;
        int exactPieces = 0;
        for (const Piece& p : pieces) {
            double c[4], sScale;
            bool exact = false;
            glm::dvec3 w0, w1;
            onePiece(p, f, c, sScale, exact, w0, w1);
            exactPieces += exact;
            expected.push_back({bits(c[0]), bits(c[1]), bits(c[2]), bits(c[3]), bits(sScale), bits(exact ? 1.0 : 0.0),
                                bits(w0.x), bits(w0.y), bits(w0.z), bits(w1.x), bits(w1.y), bits(w1.z)});
        }
        CHECK(exactPieces >= 10);  // the constant cells at least
        for (std::int64_t target : targets) {
            hwy::SetSupportedTargetsForTest(target);
            INFO(hwy::TargetName(target));
            for (std::size_t first = 0; first < pieces.size(); first += PieceBatch::kCapacity) {
                const int count = static_cast<int>(std::min<std::size_t>(PieceBatch::kCapacity, pieces.size() - first));
                PieceBatch b;
                for (int j = 0; j < count; ++j) {
                    const Piece& p = pieces[first + j];
                    for (int k = 0; k < 8; ++k) b.corner[k][j] = p.corner[k];
                    for (int a = 0; a < 3; ++a) b.cell[a][j] = p.cell[a];
                    b.phiA[j] = p.phiA;
                    b.phiB[j] = p.phiB;
                    const auto [lowest, highest] = std::minmax_element(p.corner.begin(), p.corner.end());
                    b.magnitude[j] = std::max(std::abs(*lowest), std::abs(*highest));
                }
                vri::formPieceCubics(b, count, f);
                for (int j = 0; j < count; ++j) {
                    CAPTURE(frameIndex);
                    CAPTURE(first + j);
                    const PieceBits got = {bits(b.c[0][j]),   bits(b.c[1][j]),  bits(b.c[2][j]),  bits(b.c[3][j]),
                                           bits(b.sScale[j]), bits(b.exact[j]), bits(b.w0[0][j]), bits(b.w0[1][j]),
                                           bits(b.w0[2][j]),  bits(b.w1[0][j]), bits(b.w1[1][j]), bits(b.w1[2][j])};
                    CHECK(got == expected[first + j]);
                }
            }
        }
        hwy::SetSupportedTargetsForTest(0);
    }
}
