#include "libvri/render/render_json.h"

#include <algorithm>
#include <variant>

#include "libvri/core/sparse_volume.h"

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
    const double samplesPerSecond = s.seconds > 0 ? s.samplesEvaluated / s.seconds : 0.0;
    nlohmann::json j = {{"wall_seconds", s.seconds},
                        {"setup_seconds", s.setupSeconds},
                        {"setup_reused", s.setupReused},
                        {"threads", s.threads},
                        {"rays", s.rays},
                        {"rays_hit", s.raysHit},
                        {"samples_placed", s.samplesPlaced},
                        {"samples_evaluated", s.samplesEvaluated},
                        {"samples_per_second", samplesPerSecond},
                        {"empty_brick_fraction", s.emptyBrickFraction},
                        // Rays ended early, and the most their samples left out could add to a channel.
                        {"rays_terminated", s.raysTerminated},
                        {"termination_left_out_max", s.terminationLeftOut},
                        {"backend", s.backend}};
    if (!s.device.empty()) j["device"] = s.device;
    if (!s.interpolation.empty()) j["interpolation"] = s.interpolation;
    if (s.backend == "cpu") j["simd_target"] = s.simdTarget.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.simdTarget);
    if (!s.voxelLoads.empty()) j["voxel_loads"] = s.voxelLoads;
    if (s.adaptive) j["adaptive"] = toJson(*s.adaptive);  // the Simpson methods
    if (s.simpsonRange)  // and on the CPU, their steps against the range where they mean something
        j["simpson_range"] = {{"tau_h_limit", s.simpsonRange->limit},
                              {"largest_tau_h", s.simpsonRange->largest},
                              {"pixels_beyond", s.simpsonRange->pixelsBeyond}};
    if (s.preintegration) {  // the table's own error: the largest |lookup - direct evaluation| it found
        const RenderStats::Preintegration& p = *s.preintegration;
        j["preintegration"] = {{"size", p.size},
                               {"order", p.order},
                               {"segment_length", p.segmentLength},
                               {"table_error_colour", p.error.colour},
                               {"table_error_alpha", p.error.alpha},
                               {"table_points_checked", p.error.points},
                               {"table_checked_deltas", p.error.deltas}};
    }
    j["nonfinite_pixels"] = s.nonfinite.count;
    if (s.nonfinite.count > 0) j["first_nonfinite_pixel"] = {s.nonfinite.firstX, s.nonfinite.firstY};
    return j;
}

nlohmann::json toJson(const AdaptiveCounts& c) {
    return {{"inner_tries", c.innerTries},       {"inner_failures", c.innerFailures},
            {"outer_tries", c.outerTries},       {"outer_failures", c.outerFailures},
            {"outer_steps", c.outerSteps},       {"accepted_at_h_min_above_tolerance", c.acceptedAtMinimum},
            {"points_used", c.pointsUsed},       {"points_evaluated", c.pointsEvaluated}};
}

nlohmann::json toJson(const OutOfRangePixels& o) {
    return {{"pixels", o.pixels},
            {"channels_above_1", o.channelsAbove},
            {"channels_below_0", o.channelsBelow},
            {"max", o.max},
            {"min", o.min}};
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
    } else {
        j["kind"] = "analytic";
        j["field"] = "linear: f = (x - box_lo.x) / (box_hi.x - box_lo.x)";
    }
    return j;
}

}  // namespace vri
