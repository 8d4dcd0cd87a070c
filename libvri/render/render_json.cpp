#include "libvri/render/render_json.h"

#include <algorithm>
#include <variant>

#include "libvri/core/brick_volume.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/render/stats_schema.h"

namespace vri {

namespace {
nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

nlohmann::json toJson(const RenderRequest& request) {
    nlohmann::json j = nlohmann::json::object();
    // A dotted name ("early_termination.bound") is a member of an object.
    for (const Setting& s : settingsRecord(request)) {
        std::string pointer = "/";
        pointer += s.name;
        std::replace(pointer.begin(), pointer.end(), '.', '/');
        std::visit([&](const auto& value) { j[nlohmann::json::json_pointer(pointer)] = value; }, s.value);
    }
    return j;
}

nlohmann::json toJson(const RenderStats& s) {
    using namespace stats_field;
    nlohmann::json record;
    putFrameWork(record, s);
    put(record, samplesPlaced, s.samplesPlaced);
    put(record, samplesEvaluated, s.samplesEvaluated);
    put(record, samplesPerSecond, s.seconds > 0 ? s.samplesEvaluated / s.seconds : 0.0);
    put(record, emptyBrickFraction, s.emptyBrickFraction);
    // Rays ended early, and the most their samples left out could add to a channel.
    put(record, raysTerminated, s.raysTerminated);
    put(record, terminationLeftOutMax, s.terminationLeftOut);
    put(record, backend, s.backend);
    if (!s.device.empty()) put(record, device, s.device);
    if (!s.interpolation.empty()) put(record, interpolation, s.interpolation);
    if (s.backend == "cpu") put(record, simdTarget, s.simdTarget.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.simdTarget));
    if (!s.voxelLoads.empty()) put(record, voxelLoads, s.voxelLoads);
    if (s.adaptive) {  // the Simpson methods
        const AdaptiveCounts& c = *s.adaptive;
        put(record, adaptiveInnerTries, c.innerTries);
        put(record, adaptiveInnerFailures, c.innerFailures);
        put(record, adaptiveOuterTries, c.outerTries);
        put(record, adaptiveOuterFailures, c.outerFailures);
        put(record, adaptiveOuterSteps, c.outerSteps);
        put(record, adaptiveAcceptedAtMinimum, c.acceptedAtMinimum);
        put(record, adaptivePointsUsed, c.pointsUsed);
        put(record, adaptivePointsEvaluated, c.pointsEvaluated);
    }
    if (s.simpsonRange) {  // and on the CPU, their steps against the range where they mean something
        put(record, simpsonRangeLimit, s.simpsonRange->limit);
        put(record, simpsonRangeLargest, s.simpsonRange->largest);
        put(record, simpsonRangePixelsBeyond, s.simpsonRange->pixelsBeyond);
    }
    if (s.preintegration) {  // the table's own error: the largest |lookup - direct evaluation| it found
        const RenderStats::Preintegration& p = *s.preintegration;
        put(record, preintSize, p.size);
        put(record, preintOrder, p.order);
        put(record, preintSegmentLength, p.segmentLength);
        put(record, preintErrorColour, p.error.colour);
        put(record, preintErrorAlpha, p.error.alpha);
        put(record, preintPointsChecked, p.error.points);
        if (p.order == 2) {
            put(record, preintCheckedDeltas, p.error.deltas);
            put(record, preintErrorColourByDelta, p.error.colourByDelta);
            put(record, preintErrorAlphaByDelta, p.error.alphaByDelta);
        }
        if (p.largestDelta) {
            const auto [colour, alpha] = p.error.upTo(*p.largestDelta);
            put(record, preintLargestDelta, *p.largestDelta);
            put(record, preintLookupsByDelta, p.lookupsByDelta);
            put(record, preintErrorColourUsed, colour);
            put(record, preintErrorAlphaUsed, alpha);
        }
    }
    put(record, nonfinitePixels, s.nonfinite.count);
    if (s.nonfinite.count > 0) put(record, firstNonfinitePixel, {s.nonfinite.firstX, s.nonfinite.firstY});
    return std::move(record["stats"]);
}

void putOutOfRange(nlohmann::json& record, const OutOfRangePixels& o) {
    using namespace stats_field;
    put(record, outOfRangePixels, o.pixels);
    put(record, outOfRangeAbove, o.channelsAbove);
    put(record, outOfRangeBelow, o.channelsBelow);
    put(record, outOfRangeMax, o.max);
    put(record, outOfRangeMin, o.min);
}

nlohmann::json toJson(const CameraSpec& c) {
    return {{"eye", vec(c.eye)},           {"target", vec(c.target)}, {"up", vec(c.up)},
            {"fov_y_degrees", c.fovYDegrees}, {"width", c.width},     {"height", c.height},
            {"zoom", c.zoom},
            {"zoom_centre", c.zoomCentre ? nlohmann::json{c.zoomCentre->x, c.zoomCentre->y} : nlohmann::json()}};
}

nlohmann::json toJson(const PixelRegion& r) {
    return {{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
}

nlohmann::json toJson(const TransferFunction& tf) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : tf.points()) points.push_back({p.s, p.r, p.g, p.b, p.tau});
    return {{"emission", emissionModelName(tf.emission())}, {"points_s_r_g_b_tau", points}};
}

nlohmann::json describeScene(const Scene& scene) {
    const Box box = scene.box();
    nlohmann::json j = {{"convention", gridConventionName(scene.convention)},
                        {"box_lo", vec(box.lo)},
                        {"box_hi", vec(box.hi)},
                        {"dims", vec(scene.dims())}};
    if (scene.volume) {
        const ValueRange r = scene.volume->normalisationRange();
        j["kind"] = "volume";
        j["voxel_type"] = voxelTypeName(scene.volume->type);
        j["spacing"] = vec(scene.volume->spacing);
        j["normalisation_range"] = {r.lo, r.hi};
        j["storage"] = "dense";
        j["volume_bytes"] = scene.volume->byteCount();
    } else if (scene.sparse) {
        const SparseVolume& v = *scene.sparse;
        const ValueRange r = v.normalisationRange();
        j["kind"] = "volume";
        j["voxel_type"] = voxelTypeName(v.type);
        j["spacing"] = vec(v.spacing);
        j["normalisation_range"] = {r.lo, r.hi};
        j["storage"] = "sparse";
        j["volume_bytes"] = v.byteCount();  // the stored bricks and the brick table
        j["background"] = v.background();
        j["bricks"] = v.brickCount();
        j["stored_bricks"] = v.storedBricks();
    } else if (scene.brick) {
        const BrickVolume& b = *scene.brick;
        const ValueRange r = *b.voxels.range;
        const VoxelBox stored = b.stored();
        const auto triple = [](glm::ivec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
        j["kind"] = "volume";
        j["voxel_type"] = voxelTypeName(b.voxels.type);
        j["spacing"] = vec(b.voxels.spacing);
        j["normalisation_range"] = {r.lo, r.hi};
        j["storage"] = "brick";
        j["volume_bytes"] = b.voxels.byteCount();  // the brick's stored box
        j["brick"] = {{"grid", triple(b.grid.counts())},
                      {"index", triple(b.brick)},
                      {"stored_lo", triple(stored.lo)},
                      {"stored_hi", triple(stored.hi)}};
    } else {
        j["kind"] = "analytic";
        j["field"] = "linear: f = (x - box_lo.x) / (box_hi.x - box_lo.x)";
    }
    return j;
}

}  // namespace vri
