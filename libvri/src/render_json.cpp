#include "vri/render_json.h"

namespace vri {

namespace {
nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

nlohmann::json toJson(const RenderOptions& o) {
    return {{"method", integratorName(o.integrator)},
            {"placement", placementName(o.placement)},
            {"sampling_rate", o.samplingRate},
            {"step_voxels", 1.0 / o.samplingRate},
            {"precision", precisionName(o.precision)},
            {"early_termination", o.earlyTermination},
            {"skip_empty_space", o.skipEmptySpace},
            {"tile_size", o.tileSize}};
}

nlohmann::json toJson(const RenderStats& s) {
    const double samplesPerSecond = s.seconds > 0 ? s.samplesEvaluated / s.seconds : 0.0;
    return {{"wall_seconds", s.seconds},
            {"setup_seconds", s.setupSeconds},
            {"threads", s.threads},
            {"rays", s.rays},
            {"rays_hit", s.raysHit},
            {"samples_placed", s.samplesPlaced},
            {"samples_evaluated", s.samplesEvaluated},
            {"samples_per_second", samplesPerSecond},
            {"empty_brick_fraction", s.emptyBrickFraction}};
}

nlohmann::json toJson(const CameraSpec& c) {
    return {{"eye", vec(c.eye)},           {"target", vec(c.target)}, {"up", vec(c.up)},
            {"fov_y_degrees", c.fovYDegrees}, {"width", c.width},     {"height", c.height},
            {"zoom", c.zoom},
            {"zoom_centre", c.zoomCentre ? nlohmann::json{c.zoomCentre->x, c.zoomCentre->y} : nlohmann::json()}};
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
    } else {
        j["kind"] = "analytic";
        j["field"] = "linear: f = (x - box_lo.x) / (box_hi.x - box_lo.x)";
    }
    return j;
}

}  // namespace vri
