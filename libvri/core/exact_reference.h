#pragma once
// The accurate reference: the volume rendering integral along each pixel's ray solved to near double
// precision, with a bound on its own error. The ray (the same as render()'s) is split at every plane
// where the trilinear interpolant changes form (integer voxel-index planes, including the clamp
// planes at index 0 and n - 1), so that on each piece the scalar is a cubic in t; each piece is split
// again where the cubic crosses a transfer-function breakpoint, so that extinction and colour are
// cubics too. The optical depth is then an exact quartic, and only the outer integral is computed
// numerically: by the cheapest Gauss rule (1-3 points on up to 64 equal panels) whose rigorous error
// bound, from bounds on the integrand's derivatives (gauss_error_bound.h), reaches the tolerance, and
// where none does by adaptive Gauss-Kronrod (7-15) quadrature. Paper B's own reference, a Riemann sum
// with a 0.01-voxel step, is render() with those options.
//
// The model it is exact for, stated so that every method means the same scene: voxel i's scalar is
// s_i = (v_i - lo) * r in double, r = 1 / (hi - lo) in double (lo..hi the normalisation range), as every
// renderer of vri computes it; between voxels the trilinear interpolant of the s_i; at a TF point where the
// TF jumps, the value from the point on (right-continuous), as TransferFunction::operator() reads it. A cell
// whose eight corners hold one value is therefore known exactly, and a TF point placed at that value (as TF
// editors for 8-bit data place them) costs its bound nothing.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/image.h"

namespace vri {

class OccupancyCache;  // occupancy_cache.h

struct ExactReferenceOptions {
    // Each transfer-function sub-piece's quadrature error for the pixel (weighted by the transparency
    // in front of it) is kept below this: the Gauss rule's derivative bound, or where no Gauss rule
    // reaches it the adaptive quadrature's estimate |K - G| (from 1e-8 up the 3-7 Gauss-Kronrod rule
    // replaces the 7-15 one). The pixel's bound sums these over its sub-pieces, so it is a few to a
    // few tens of times this. A ray also ends once the transparency times the largest colour (and the
    // transparency itself, for alpha) is below it; that tail is in the bound.
    double tolerance = 1e-13;
    // Jump over blocks of 4^3 cells and regions of 32^3 on which the transfer function is zero
    // (exact_empty_space.h: the image and the bounds do not change by a bit; off only to test that).
    bool skipEmptySpace = true;
    int tileSize = 16;
    // The Highway target the Gauss batches run on (simd_target.h; `--simd`): empty for VRI_SIMD_TARGET's,
    // else the best. Every target gives the same image and bounds bit for bit; only the time differs.
    std::string simdTarget;
    std::optional<PixelRegion> region;  // only these pixels of the camera's image (RenderOptions::region)
    bool progress = false;  // report progress on stderr
};

struct ExactReferenceStats {
    std::uint64_t rays = 0;               // pixels (of the region, when there is one)
    std::uint64_t raysHit = 0;            // rays whose segment in the box has positive length
    std::uint64_t pieces = 0;             // cell pieces walked (the scalar is one cubic on each)
    std::uint64_t piecesVisible = 0;      // of those, the ones not skipped as invisible
    std::uint64_t subPieces = 0;          // transfer-function sub-pieces integrated
    std::uint64_t quadratureIntervals = 0;  // intervals integrated (sub-pieces plus subdivisions)
    std::uint64_t quadratureNodes = 0;    // integrand evaluations of the Gauss-Kronrod rules (7 or 15 each)
    std::uint64_t raysOpaque = 0;         // rays ended early: what was left could add at most the tolerance
    // Rays with a sub-piece whose bound counted all of it as possibly beyond its TF segment (ExactRay::
    // wholeSubPieceWindow): s within rounding of a TF point along it, as far as could be shown.
    std::uint64_t raysWholeSubPieceWindow = 0;
    double seconds = 0.0;       // the frame's own work, without setupSeconds unless reused
    double setupSeconds = 0.0;  // building the empty space (exact_empty_space.h), this frame or an earlier one
    bool setupReused = false;   // the empty space came from an earlier frame (occupancy_cache.h)
    int threads = 0;
    std::string simdTarget;  // the Gauss batches' Highway target ("AVX2", ...); empty below kGaussTolerance
    // Per channel R, G, B, A over all pixels: the largest and the mean error bound. These bound the
    // values in double (ExactReference::values), before any rounding to float32.
    std::array<double, 4> maxBound{}, meanBound{};
    // Per channel: the largest rounding of a value to float32 (|float(v) - v|, at most half an ulp of
    // the float), and the largest bound on the float32 value's error, bound + that rounding (what
    // ExactReference::image() and boundImage() hold).
    std::array<double, 4> maxFloatRounding{}, maxStoredBound{};
};

// The result in double, pixel-interleaved RGBA with row 0 at the top like render()'s Image, and for
// every pixel and channel a bound on |value - exact integral along the ray|.
struct ExactReference {
    int width = 0, height = 0;  // the region's, when the options name one
    std::vector<double> values;  // width * height * 4
    std::vector<double> bounds;  // width * height * 4
    ExactReferenceStats stats;

    Image image() const;  // the values as float RGBA (its rounding often exceeds the double's bound)
    // A bound on each of image()'s values, channels R, G, B, A: the double's bound plus its rounding to
    // float32, rounded up to a float (so it bounds what the EXR holds, not just the double).
    Image boundImage() const;
};

// The same rays as render(scene, camera, ...). With a cache, the empty space of an earlier frame of
// the same volume and transfer function is reused. Throws vri::Error on a scene without volume or field,
// a node-centred volume thinner than 2 voxels, a tolerance that is not positive, an extinction whose
// optical depth across the box overflows double, or any pixel whose value or bound is not finite.
ExactReference renderExactReference(const Scene& scene, const Camera& camera,
                                    const ExactReferenceOptions& options = {}, OccupancyCache* cache = nullptr);
// The same into `out`, whose buffers keep their memory: a sequence of frames pays for touching a fresh
// 31 MB (800x600: values and bounds in double) once, not every frame (on a virtual machine the page
// faults took about 5 % of a Bonsai frame).
void renderExactReference(const Scene& scene, const Camera& camera, const ExactReferenceOptions& options,
                          OccupancyCache* cache, ExactReference& out);

}  // namespace vri
