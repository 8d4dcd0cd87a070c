#pragma once
// vri-render --method exact and vri-reference's --max-error: the tolerance that keeps every pixel's
// error bound within E, searched with renders of the exact method.
#include <nlohmann/json.hpp>

#include "libvri/render/render_backend.h"
#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/render_option_table.h"

namespace vri {

// --max-error E: the exact method's tolerance bounds the quadrature per piece of a ray, not a pixel's error;
// the stats' per-pixel bound is what E asks for. A pixel's bound sums its pieces' errors, so it grows
// about in proportion to the tolerance, by a factor that depends on the scene and view. The search:
//  - from --tolerance (else E), each further render at the tolerance times E / bound / 2;
//  - first a pilot, the same view at a quarter of each side (1/16 of the work; not for a --region, nor an
//    image under 128 pixels a side), until its largest bound is at most 0.6 E (the factor is not constant
//    over decades of tolerance: rays end sooner at a loose one), at most 8 renders;
//  - then the image, until its largest bound is at most E, at most 8 renders; from the pilot's
//    tolerance, one is the rule;
//  - either ends with an error where the bound stops following the tolerance (max_error_search.cpp).
// The last, accepted render is a frame at the tolerance found: the caller uses it as its first frame.
struct MaxErrorSearch {
    double tolerance;
    const ExactReference* accepted;  // the backend's last frame, at `tolerance`
    nlohmann::json record;           // the stats' "max_error_search"
};

// Runs the search above with `backend` (whose last frame `accepted` is), for `request` (its --max-error,
// --tolerance, --simd and --region) and the frames' camera (the pilot's is made from its spec); throws
// vri::Error when E is out of reach.
MaxErrorSearch searchMaxErrorTolerance(RenderBackend& backend, const Scene& scene, const Camera& camera,
                                       const RenderRequest& request);

}  // namespace vri
