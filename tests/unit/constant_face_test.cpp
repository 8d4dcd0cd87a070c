// The factorisation constant_face.h rests on: where a cell face's four corners hold one scalar v, the
// trilinear interpolant along a piece is v + F G, F the ray's weight-distance from the face and G the
// returned quadratic; and G's computed values lie within their stated rounding of the model's.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "libvri/core/constant_face.h"
#include "libvri/core/segment_kernel.h"

using namespace vri;

namespace {

// The trilinear interpolant of the corners at cell weights w, in long double (64-bit mantissa): an arbiter
// some 2^11 finer than the double arithmetic under test.
long double trilinear(const std::array<double, 8>& s, const long double w[3]) {
    long double sum = 0.0L;
    for (int k = 0; k < 8; ++k) {
        long double weight = 1.0L;
        for (int a = 0; a < 3; ++a) weight *= (k >> a & 1) ? w[a] : 1.0L - w[a];
        sum += weight * s[k];
    }
    return sum;
}

}  // namespace

TEST_CASE("constant faces: s - v is F times G along the piece, G within its rounding") {
    std::mt19937_64 random(20261207);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int faces = 0, overshoots = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const int a = trial % 3, e = trial / 3 % 2;
        std::array<double, 8> s;
        const double v = std::floor(256.0 * unit(random)) / 255.0;
        for (int k = 0; k < 8; ++k) s[k] = (k >> a & 1) == e ? v : std::floor(256.0 * unit(random)) / 255.0;
        glm::dvec3 w0, w1;
        for (int b = 0; b < 3; ++b) w0[b] = unit(random), w1[b] = unit(random);
        if (trial % 5 == 0) w1[a] = e;                    // the piece ends on the face
        if (trial % 7 == 0 && trial % 5 != 0) w0[a] = e;  // or starts there
        ConstantFace out[6];
        const int count = constantFaces(s, w0, w1, out);
        const ConstantFace* face = nullptr;
        for (int f = 0; f < count; ++f) face = out[f].value == v ? &out[f] : face;
        REQUIRE(face != nullptr);
        ++faces;
        const double eps = 48.0 * segment_kernel::kUnit * face->scale;
        for (double sigma : {0.0, 1e-9, 0.25, 0.5, 0.999, 1.0}) {
            long double w[3];
            for (int b = 0; b < 3; ++b) w[b] = w0[b] + static_cast<long double>(w1[b] - w0[b]) * sigma;
            // s - v = F G, with G known to eps (the arbiter's own rounding is some 1e-18 of these magnitudes). F is
            // w_a - e signed towards the cell: a piece ending on the face may overshoot it by an ulp of its weight
            // (w0 + (w1 - w0) with the difference rounded), where F, and s - v with it, changes sign.
            const long double f = e == 0 ? w[a] : 1.0L - w[a], model = trilinear(s, w) - v;
            const long double error = std::fabs(model - f * static_cast<long double>(face->g(sigma)));
            CHECK(error <= std::fabs(f) * eps + 1e-17L);
            overshoots += f < 0.0L;
        }
    }
    CHECK(faces == 2000);
    CHECK(overshoots > 0);  // the case exact_ray.cpp's faceWidth counts a sliver of u for
    // A piece lying in the face (both weights on it) is not beside it: no face there.
    const std::array<double, 8> zeros{};
    ConstantFace out[6];
    CHECK(constantFaces(zeros, {0.0, 0.3, 0.2}, {0.0, 0.9, 0.7}, out) == 5);  // all six constant, x = 0 left out
}
