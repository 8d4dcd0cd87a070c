#include "libvri/render/image_compare_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

namespace vri {

nlohmann::json toJson(const ImageMetrics& metrics) {
    // JSON has no infinity: the PSNR of equal images is null, read as infinite.
    const auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
    const auto values = [&](const MetricValues& v) {
        return nlohmann::json{{"psnr_db", finite(v.psnr)}, {"ssim", finite(v.ssim)}, {"rel_mse", finite(v.relMse)},
                              {"smape", finite(v.smape)}};
    };
    nlohmann::json channels = nlohmann::json::array();
    for (std::size_t c = 0; c < metrics.channels.size(); ++c) {
        nlohmann::json one = values(metrics.channels[c]);
        one["name"] = metrics.channelNames[c];
        channels.push_back(std::move(one));
    }
    return {{"all", values(metrics.all)},
            {"channels", std::move(channels)},
            {"psnr_peak", kPsnrPeak},
            {"ssim", "Wang et al. 2004: Gaussian window 11, sigma 1.5, K1 0.01, K2 0.03, L 1, each channel alone, "
                     "the mean over the windows that fit (all channels: the mean of the channels')"},
            {"relative_epsilon", kRelativeEpsilon},
            {"ssim_windows", metrics.ssimWindows}};
}

nlohmann::json toJson(const ImageDiff& diff) {
    nlohmann::json channels = nlohmann::json::array();
    for (const ChannelDiff& channel : diff.channels) {
        nlohmann::json above = nlohmann::json::array();
        for (std::size_t t = 0; t < diff.thresholds.size(); ++t)
            above.push_back({{"threshold", diff.thresholds[t]},
                             {"count", channel.countAbove[t]},
                             {"percent", channel.percentAbove[t]}});
        channels.push_back({{"name", channel.name},
                            {"max_abs", channel.maxAbs},
                            {"max_at", {channel.maxX, channel.maxY}},
                            {"mean_abs", channel.meanAbs},
                            {"rmse", channel.rmse},
                            {"above", std::move(above)}});
    }
    return {{"width", diff.width},
            {"height", diff.height},
            {"pixels", diff.pixels},
            {"pixels_counted", diff.mask == kAllPixels ? std::string("all") : diff.mask},
            {"thresholds", diff.thresholds},
            {"channels", std::move(channels)}};
}

}  // namespace vri
