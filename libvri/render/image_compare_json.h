#pragma once
// ImageDiff as JSON, kept apart from image_compare.h so that its many includers do not pay for
// nlohmann/json. Include <nlohmann/json.hpp> where the result is used.
#include <nlohmann/json_fwd.hpp>

#include "libvri/core/image_compare.h"
#include "libvri/core/image_metrics.h"

namespace vri {

// {"width", "height", "pixels", "pixels_counted": "all" or the mask's description, "thresholds": [...],
//  "channels": [{"name", "max_abs", "max_at": [x, y], "mean_abs", "rmse",
//                "above": [{"threshold", "count", "percent"}, ...]}, ...]}
// Infinite errors (NaN against a number) have no JSON number and appear as null.
nlohmann::json toJson(const ImageDiff& diff);

// {"all": {"psnr_db", "ssim", "rel_mse", "smape"}, "channels": [{"name", ...the same}], "psnr_peak",
//  "ssim" (its parameters in words), "relative_epsilon", "ssim_windows"}; an infinite PSNR (equal images) and
// a NaN SSIM (an image smaller than the window) are null.
nlohmann::json toJson(const ImageMetrics& metrics);

}  // namespace vri
