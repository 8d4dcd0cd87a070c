#include "libvri/render/exact_reference_json.h"

#include "libvri/render/render_json.h"  // putFrameWork

namespace vri {

nlohmann::json toJson(const ExactReferenceStats& s) {
    using namespace stats_field;
    nlohmann::json record;
    putFrameWork(record, s);
    // The batched Gauss rules' Highway target; null where the tolerance keeps them scalar.
    put(record, simdTarget, s.simdTarget.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.simdTarget));
    put(record, raysOpaque, s.raysOpaque);
    put(record, raysWholeSubPieceWindow, s.raysWholeSubPieceWindow);
    put(record, pieces, s.pieces);
    put(record, piecesVisible, s.piecesVisible);
    put(record, subPieces, s.subPieces);
    put(record, quadratureIntervals, s.quadratureIntervals);
    put(record, quadratureNodes, s.quadratureNodes);
    // Per channel R, G, B, A, over all pixels (rays that miss the box have bound 0): max and mean bound the
    // values in double; the EXR's float32 values add their rounding (stored_max, what --error-image holds
    // per pixel).
    put(record, errorBoundChannels, {"R", "G", "B", "A"});
    put(record, errorBoundAppliesTo, "double value before float32 rounding");
    put(record, errorBoundMax, s.maxBound);
    put(record, errorBoundMean, s.meanBound);
    put(record, errorBoundRoundingMax, s.maxFloatRounding);
    put(record, errorBoundStoredMax, s.maxStoredBound);
    put(record, errorBoundErrorImage, "bound on the stored float32 value: the double's bound plus its float32 rounding, rounded up");
    return std::move(record["stats"]);
}

}  // namespace vri
