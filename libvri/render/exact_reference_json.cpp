#include "libvri/render/exact_reference_json.h"

namespace vri {

nlohmann::json toJson(const ExactReferenceStats& s) {
    return {{"wall_seconds", s.seconds},
            {"setup_seconds", s.setupSeconds},
            {"setup_reused", s.setupReused},
            {"threads", s.threads},
            // The batched Gauss rules' Highway target; null where the tolerance keeps them scalar.
            {"simd_target", s.simdTarget.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.simdTarget)},
            {"rays", s.rays},
            {"rays_hit", s.raysHit},
            {"rays_opaque", s.raysOpaque},
            {"pieces", s.pieces},
            {"pieces_visible", s.piecesVisible},
            {"sub_pieces", s.subPieces},
            {"quadrature_intervals", s.quadratureIntervals},
            {"quadrature_nodes", s.quadratureNodes},
            // Per channel R, G, B, A, over all pixels (rays that miss the box have bound 0): max and mean
            // bound the values in double; the EXR's float32 values add their rounding (stored_max, what
            // --error-image holds per pixel).
            {"error_bound",
             {{"channels", {"R", "G", "B", "A"}},
              {"applies_to", "double value before float32 rounding"},
              {"max", s.maxBound},
              {"mean", s.meanBound},
              {"float32_rounding_max", s.maxFloatRounding},
              {"stored_max", s.maxStoredBound},
              {"error_image", "bound on the stored float32 value: the double's bound plus its float32 rounding, "
                              "rounded up"}}}};
}

}  // namespace vri
