#pragma once
// JSON records of a render's settings and statistics, as written in stats files and manifests.
#include <nlohmann/json.hpp>

#include "vri/core/camera.h"
#include "vri/core/cpu_renderer.h"

namespace vri {

nlohmann::json toJson(const RenderOptions& options);
nlohmann::json toJson(const RenderStats& stats);
nlohmann::json toJson(const AdaptiveCounts& counts);
nlohmann::json toJson(const CameraSpec& camera);
nlohmann::json toJson(const TransferFunction& tf);
nlohmann::json describeScene(const Scene& scene);  // kind, dims, voxel type, spacing, box, convention, range

}  // namespace vri
