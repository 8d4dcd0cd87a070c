#include "libvri/core/constant_face.h"

#include <algorithm>
#include <cmath>

namespace vri {

int constantFaces(const std::array<double, 8>& s, const glm::dvec3& w0, const glm::dvec3& w1, ConstantFace out[6]) {
    int count = 0;
    for (int a = 0; a < 3; ++a)
        for (int e = 0; e < 2; ++e) {
            // Corner k is on the face where bit a of k is e; its opposite across the cell has bit a flipped.
            const int faceBit = e << a, axisBit = 1 << a;
            double value = 0.0;
            bool constant = true;
            for (int k = 0, seen = 0; k < 8; ++k)
                if ((k & axisBit) == faceBit) {
                    if (seen++ == 0) value = s[k];
                    constant = constant && s[k] == value;
                }
            // A piece lying in the face (both its weights on it) has F = 0 all along: s is v there, not beside it.
            if (!constant || (w0[a] == e && w1[a] == e)) continue;
            // G as the trilinear interpolant of a cell whose two faces across axis a both hold the opposite
            // face's s_k - v: independent of w_a (its lerp along a is of equal values, exact), the same
            // three lerps as the piece's cubic, so its coefficients carry the same rounding: 32 u of the
            // magnitudes involved (exact_ray.cpp's error analysis), whose scale adds the corners' own
            // rounding of s_k - v, u of each.
            std::array<double, 8> d;
            double largest = 0.0;
            for (int k = 0; k < 8; ++k) {
                d[k] = s[(k & ~axisBit) | (faceBit ^ axisBit)] - value;
                largest = std::max(largest, std::abs(d[k]));
            }
            ConstantFace& face = out[count++];
            face.value = value;
            face.g = trilinearAlongSegment(d, w0, w1);
            face.scale = std::abs(face.g.c[0]) + std::abs(face.g.c[1]) + std::abs(face.g.c[2]) + std::abs(face.g.c[3]) +
                         2.0 * largest;
        }
    return count;
}

}  // namespace vri
