#include "common/exact_reference_json.h"

namespace vri {

nlohmann::json toJson(const ExactReferenceStats& s) {
    return {{"wall_seconds", s.seconds},
            {"setup_seconds", s.setupSeconds},
            {"setup_reused", s.setupReused},
            {"threads", s.threads},
            {"rays", s.rays},
            {"rays_hit", s.raysHit},
            {"rays_opaque", s.raysOpaque},
            {"pieces", s.pieces},
            {"pieces_visible", s.piecesVisible},
            {"sub_pieces", s.subPieces},
            {"quadrature_intervals", s.quadratureIntervals},
            {"quadrature_nodes", s.quadratureNodes},
            // Per channel R, G, B, A, over all pixels (rays that miss the box have bound 0).
            {"error_bound", {{"channels", {"R", "G", "B", "A"}}, {"max", s.maxBound}, {"mean", s.meanBound}}}};
}

}  // namespace vri
