#pragma once
// JSON records of a render's settings and statistics, as written in stats files and manifests.
#include <nlohmann/json.hpp>

#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/out_of_range_pixels.h"
#include "libvri/core/render_option_table.h"
#include "libvri/render/stats_schema.h"

namespace vri {

// The settings record of a render (settingsRecord(), render_option_table.h) as a JSON object.
nlohmann::json toJson(const RenderRequest& request);
// The "stats" record of a render, its fields as the stats schema names them (stats_schema.h).
nlohmann::json toJson(const RenderStats& stats);
// The fields every method's stats have (RenderStats, ExactReferenceStats): the frame's work and its rays.
template <class Stats>
void putFrameWork(nlohmann::json& record, const Stats& s) {
    using namespace stats_field;
    put(record, wallSeconds, s.seconds);
    put(record, setupSeconds, s.setupSeconds);
    put(record, setupReused, s.setupReused);
    put(record, threads, s.threads);
    put(record, rays, s.rays);
    put(record, raysHit, s.raysHit);
}
// Sets a stats file's stats.out_of_range_pixels (stats_schema.h) to what was found.
void putOutOfRange(nlohmann::json& record, const OutOfRangePixels& found);
nlohmann::json toJson(const CameraSpec& camera);
nlohmann::json toJson(const PixelRegion& region);  // {"x", "y", "width", "height"}
nlohmann::json toJson(const TransferFunction& tf);
nlohmann::json describeScene(const Scene& scene);  // kind, dims, voxel type, spacing, box, convention, range

}  // namespace vri
