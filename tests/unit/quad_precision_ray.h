#pragma once
// The emission-absorption integral along vri's own ray, in quadruple precision (__float128,
// libquadmath): an arbiter for the exact method's per-pixel bound that shares none of its code. The ray is
// what vri makes of a pixel (camera, clipRay, Box::toTexture: entry and exit in texture coordinates and the
// length in world units; in a volume the line entry + phi delta of voxel-index coordinates that the exact
// method forms from them in double, the ray it integrates along); from there everything is redone in
// 113-bit arithmetic: the cell faces the ray crosses, the trilinear interpolant along each cell piece (a
// cubic, from the corners' scalars as the model defines them, exact_reference.h, and the weights), where it
// crosses each transfer-function point (bisection to the last bit), the optical depth (the exact quartic) and
// the emission integral (Gauss-Legendre 10 against 20 on intervals across which the depth grows by at most
// 1/4, bisected until they agree to 1e-26 of the value, or 1e-30). Its own error is some 1e-25 of the values,
// far below any bound in double.
#include <quadmath.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "libvri/core/cpu_renderer.h"
#include "libvri/core/camera.h"

namespace vri::test {

using Quad = __float128;

// The Gauss-Legendre rule of n points on [-1, 1] in Quad: the roots of P_n by Newton from the Chebyshev
// guess, weights 2 / ((1 - x^2) P_n'(x)^2).
struct QuadGaussRule {
    std::vector<Quad> node, weight;
    explicit QuadGaussRule(int n) {
        for (int i = 0; i < n; ++i) {
            Quad x = cosq(acosq(Quad(-1)) * (i + Quad(0.75)) / (n + Quad(0.5))), derivative = 0;
            for (int iteration = 0; iteration < 100; ++iteration) {
                Quad p0 = 1, p1 = x;
                for (int k = 2; k <= n; ++k) {
                    const Quad p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = n * (x * p1 - p0) / (x * x - 1);
                const Quad step = p1 / derivative;
                x -= step;
                if (fabsq(step) < Quad(1e-33)) break;
            }
            node.push_back(x);
            weight.push_back(2 / ((1 - x * x) * derivative * derivative));
        }
    }
};

class QuadPrecisionRay {
public:
    explicit QuadPrecisionRay(const TransferFunction& tf) : tf_(tf), low_(10), high_(20) {
        for (const auto& p : tf.points())
            if (levels_.empty() || levels_.back() != p.s) levels_.push_back(p.s);
        for (const auto& p : tf.points()) maxColour_ = std::max({maxColour_, p.r, p.g, p.b});
    }

    // RGBA of the pixel's ray through the scene (zero where it misses the box).
    std::array<Quad, 4> pixel(const Scene& scene, const Camera& camera, int px, int py) {
        colour_ = {0, 0, 0};
        depth_ = 0;
        const glm::dvec3 dir = camera.direction(px, py);
        const Box box = scene.box();
        const auto segment = clipRay(camera.eye(), dir, box);
        if (segment && segment->tFar > segment->tNear) {
            const glm::dvec3 entry = box.toTexture(camera.eye() + segment->tNear * dir);
            const glm::dvec3 exit = box.toTexture(camera.eye() + segment->tFar * dir);
            const Quad length = Quad(segment->tFar) - Quad(segment->tNear);
            if (scene.volume)
                walkVolume(*scene.volume, scene.convention, entry, exit, length);
            else  // the analytic field: s = u.x, one linear piece
                piece(length, {Quad(entry.x), Quad(exit.x) - Quad(entry.x), 0, 0});
        }
        return {colour_[0], colour_[1], colour_[2], -expm1q(-depth_)};
    }

private:
    using Poly = std::array<Quad, 4>;  // c0 + c1 x + c2 x^2 + c3 x^3 on [0, 1]
    static Quad eval(const Poly& p, Quad x) { return p[0] + x * (p[1] + x * (p[2] + x * p[3])); }

    // The cell pieces: index coordinates X(phi) = U(phi) scale - offset, U the texture coordinate, split
    // at every integer plane in [0, n - 1]; on each the interpolant is a cubic in the piece's own [0, 1].
    void walkVolume(const Volume& v, GridConvention convention, const glm::dvec3& uEntry, const glm::dvec3& uExit,
                    Quad length) {
        const bool cell = convention == GridConvention::CellCentred;
        Quad x0[3], dx[3];
        std::vector<Quad> cuts = {0, 1};
        for (int a = 0; a < 3; ++a) {
            const double scale = cell ? v.dims[a] : v.dims[a] - 1.0, offset = cell ? 0.5 : 0.0;
            const double entry = uEntry[a] * scale - offset;
            x0[a] = entry;
            dx[a] = (uExit[a] * scale - offset) - entry;
            if (dx[a] == 0) continue;
            for (int k = 0; k <= v.dims[a] - 1; ++k) {
                const Quad phi = (k - x0[a]) / dx[a];
                if (phi > 0 && phi < 1) cuts.push_back(phi);
            }
        }
        std::sort(cuts.begin(), cuts.end());
        // The model's voxel scalars (exact_reference.h): (v - lo) * r in double, r = 1 / (hi - lo) in double.
        const ValueRange range = v.normalisationRange();
        const double r = range.hi > range.lo ? 1.0 / (range.hi - range.lo) : 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
            const Quad phiA = cuts[i], phiB = cuts[i + 1];
            if (!(phiB > phiA)) continue;
            const Quad mid = (phiA + phiB) / 2;
            // Per axis the cell and the weight w(sigma) = w0 + w1 sigma (constant where clamped).
            int base[3];
            Quad w0[3], w1[3];
            for (int a = 0; a < 3; ++a) {
                const int n = v.dims[a];
                const Quad xm = x0[a] + mid * dx[a];
                const Quad clamped = xm < 0 ? Quad(0) : xm > n - 1 ? Quad(n - 1) : xm;
                base[a] = std::min(static_cast<int>(clamped), std::max(n - 2, 0));
                if (n == 1 || xm <= 0 || xm >= n - 1) {
                    w0[a] = n == 1 ? 0 : clamped - base[a];
                    w1[a] = 0;
                } else {
                    w0[a] = x0[a] + phiA * dx[a] - base[a];
                    w1[a] = (phiB - phiA) * dx[a];
                }
            }
            Quad corners[8];
            for (int k = 0; k < 8; ++k) {
                int at[3];
                for (int a = 0; a < 3; ++a) at[a] = std::min(base[a] + (k >> a & 1), v.dims[a] - 1);
                corners[k] = (voxel(v, at[0], at[1], at[2]) - range.lo) * r;
            }
            // The corners that weigh on the piece (a weight of exactly 0 or 1 all along an axis leaves out the
            // far or the near ones) holding one value: the interpolant is that value exactly, not within the
            // rounding of the sum below, which could put a cell sitting on a TF point beside it.
            std::optional<Quad> one;
            bool constant = true;
            for (int k = 0; k < 8 && constant; ++k) {
                bool weighs = true;
                for (int a = 0; a < 3; ++a)
                    if (w1[a] == 0 && w0[a] == ((k >> a & 1) ? 0 : 1)) weighs = false;
                if (!weighs) continue;
                constant = !one || *one == corners[k];
                one = corners[k];
            }
            if (constant) {
                piece((phiB - phiA) * length, {*one, 0, 0, 0});
                if (opaque()) return;
                continue;
            }
            Poly s = {0, 0, 0, 0};
            for (int k = 0; k < 8; ++k) {
                Poly product = {corners[k], 0, 0, 0};
                for (int a = 0; a < 3; ++a) {  // times w or 1 - w
                    const Quad c0 = (k >> a & 1) ? w0[a] : 1 - w0[a], c1 = (k >> a & 1) ? w1[a] : -w1[a];
                    for (int d = 3; d >= 0; --d) product[d] = product[d] * c0 + (d > 0 ? product[d - 1] * c1 : 0);
                }
                for (int d = 0; d < 4; ++d) s[d] += product[d];
            }
            piece((phiB - phiA) * length, s);
            if (opaque()) return;
        }
    }

    static double voxel(const Volume& v, int x, int y, int z) {
        const std::size_t i = v.index(x, y, z);
        switch (v.type) {
            case VoxelType::UInt8: return v.data<std::uint8_t>()[i];
            case VoxelType::UInt16: return v.data<std::uint16_t>()[i];
            default: return v.data<float>()[i];
        }
    }

    // What the rest of the ray could add is below 1e-40: g = C tau adds at most C_max T.
    bool opaque() const { return tf_.emission() == EmissionModel::ColourTimesExtinction && depth_ > 95; }

    // One piece, `length` world units, s = cubic in [0, 1]: split where s crosses a TF point.
    void piece(Quad length, const Poly& s) {
        std::vector<Quad> ends = {0};
        // s' = c1 + 2 c2 x + 3 c3 x^2: its roots in (0, 1) bound the monotone parts.
        const Quad a = 3 * s[3], b = 2 * s[2], c = s[1];
        std::vector<Quad> critical;
        if (a == 0) {
            if (b != 0) critical.push_back(-c / b);
        } else {
            const Quad disc = b * b - 4 * a * c;
            if (disc >= 0) {
                const Quad r = sqrtq(disc);
                critical.push_back((-b - r) / (2 * a));
                critical.push_back((-b + r) / (2 * a));
            }
        }
        std::sort(critical.begin(), critical.end());
        for (Quad x : critical)
            if (x > 0 && x < 1) ends.push_back(x);
        ends.push_back(1);
        std::vector<Quad> splits = {0};
        for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
            std::vector<Quad> roots;
            for (double level : levels_) {
                Quad lo = ends[i], hi = ends[i + 1];
                const Quad fLo = eval(s, lo) - level, fHi = eval(s, hi) - level;
                if (!((fLo < 0 && fHi > 0) || (fLo > 0 && fHi < 0))) continue;
                for (int k = 0; k < 120 && lo < hi; ++k) {
                    const Quad m = (lo + hi) / 2;
                    if (m <= lo || m >= hi) break;
                    if ((eval(s, m) - level < 0) == (fLo < 0)) lo = m; else hi = m;
                }
                roots.push_back((lo + hi) / 2);
            }
            std::sort(roots.begin(), roots.end());
            splits.insert(splits.end(), roots.begin(), roots.end());
            splits.push_back(ends[i + 1]);
        }
        for (std::size_t i = 0; i + 1 < splits.size() && !opaque(); ++i)
            if (splits[i + 1] > splits[i]) subPiece(length, s, splits[i], splits[i + 1]);
    }

    // A sub-piece inside one TF segment: tau and C are v + m (s - s_A).
    void subPiece(Quad length, const Poly& s, Quad x0, Quad x1) {
        const auto& p = tf_.points();
        const Quad sMid = eval(s, (x0 + x1) / 2);
        std::size_t i = 0;
        while (i + 1 < p.size() && sMid >= Quad(p[i + 1].s)) ++i;
        std::array<Quad, 4> value, slope{};  // tau, R, G, B
        const auto channels = [](const TransferFunctionPoint& q) { return std::array<double, 4>{q.tau, q.r, q.g, q.b}; };
        const auto va = channels(p[i]);
        Quad sA = p[i].s;
        for (int k = 0; k < 4; ++k) value[k] = va[k];
        if (sMid >= Quad(p.front().s) && i + 1 < p.size()) {  // else a constant beyond the first or last point
            const auto vb = channels(p[i + 1]);
            for (int k = 0; k < 4; ++k) slope[k] = (Quad(vb[k]) - Quad(va[k])) / (Quad(p[i + 1].s) - sA);
        }
        // On the sub-piece's own [0, 1] (a Taylor shift), so that the depth never cancels: tau as a cubic
        // and its integral, the depth from the sub-piece's start.
        const Quad h = x1 - x0;
        const Poly local = {eval(s, x0), h * (s[1] + x0 * (2 * s[2] + 3 * x0 * s[3])), h * h * (s[2] + 3 * x0 * s[3]),
                            h * h * h * s[3]};
        length *= h;
        // s - s_A on the sub-piece, shifted once: a pulse 1e-12 wide is then resolved to Quad's
        // precision relative to its own width, not to s.
        Poly shifted = local;
        shifted[0] -= sA;
        Poly tau;
        tau[0] = value[0] + slope[0] * shifted[0];
        for (int k = 1; k < 4; ++k) tau[k] = slope[0] * local[k];
        auto depthAt = [&](Quad x) {  // length * integral of tau from 0 to x
            return length * x * (tau[0] + x * (tau[1] / 2 + x * (tau[2] / 3 + x * tau[3] / 4)));
        };
        const bool colourTimesExtinction = tf_.emission() == EmissionModel::ColourTimesExtinction;
        const Quad front = depth_;
        auto integrand = [&](Quad x, Quad out[3]) {
            const Quad sx = eval(shifted, x);
            const Quad t = expq(-(front + depthAt(x))) * (colourTimesExtinction ? value[0] + slope[0] * sx : Quad(1));
            for (int c = 0; c < 3; ++c) out[c] = (value[c + 1] + slope[c + 1] * sx) * t;
        };
        auto rule = [&](const QuadGaussRule& g, Quad a, Quad b, Quad out[3]) {
            out[0] = out[1] = out[2] = 0;
            const Quad half = (b - a) / 2, centre = (a + b) / 2;
            for (std::size_t k = 0; k < g.node.size(); ++k) {
                Quad f[3];
                integrand(centre + half * g.node[k], f);
                for (int c = 0; c < 3; ++c) out[c] += g.weight[k] * f[c];
            }
            for (int c = 0; c < 3; ++c) out[c] *= half * length;
        };
        struct Interval {
            Quad a, b;
            int level;
        };
        std::vector<Interval> stack = {{0, 1, 0}};
        while (!stack.empty()) {
            const Interval iv = stack.back();
            stack.pop_back();
            const Quad dA = front + depthAt(iv.a), dB = front + depthAt(iv.b);
            // Nothing left to see: at most C_max T (g = C tau) or C_max T times the length (g = C).
            const Quad most = expq(-dA) * maxColour_ * (colourTimesExtinction ? 1 : length * (iv.b - iv.a));
            if (most < Quad(1e-40)) continue;
            if (dB - dA <= Quad(0.25) || iv.level >= 90) {
                Quad coarse[3], fine[3];
                rule(low_, iv.a, iv.b, coarse);
                rule(high_, iv.a, iv.b, fine);
                bool agree = true;
                for (int c = 0; c < 3; ++c) agree = agree && fabsq(fine[c] - coarse[c]) <= Quad(1e-30) + Quad(1e-26) * fabsq(fine[c]);
                if (agree || iv.level >= 90) {
                    for (int c = 0; c < 3; ++c) colour_[c] += fine[c];
                    continue;
                }
            }
            const Quad m = (iv.a + iv.b) / 2;
            stack.push_back({m, iv.b, iv.level + 1});
            stack.push_back({iv.a, m, iv.level + 1});
        }
        depth_ = front + depthAt(1);
    }

    const TransferFunction& tf_;
    QuadGaussRule low_, high_;
    std::vector<double> levels_;
    double maxColour_ = 0;
    std::array<Quad, 3> colour_{};
    Quad depth_ = 0;
};

}  // namespace vri::test
