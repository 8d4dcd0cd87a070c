#pragma once
// JSON records of a render's settings and statistics, as written in stats files and manifests.
#include <nlohmann/json.hpp>

#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/out_of_range_pixels.h"
#include "libvri/core/render_option_table.h"

namespace vri {

// The settings record of a render (settingsRecord(), render_option_table.h) as a JSON object.
nlohmann::json toJson(const RenderRequest& request);
nlohmann::json toJson(const RenderStats& stats);
nlohmann::json toJson(const AdaptiveCounts& counts);
// {"pixels", "channels_above_1", "channels_below_0", "max", "min"}
nlohmann::json toJson(const OutOfRangePixels& found);
nlohmann::json toJson(const CameraSpec& camera);
nlohmann::json toJson(const PixelRegion& region);  // {"x", "y", "width", "height"}
nlohmann::json toJson(const TransferFunction& tf);
nlohmann::json describeScene(const Scene& scene);  // kind, dims, voxel type, spacing, box, convention, range

}  // namespace vri
