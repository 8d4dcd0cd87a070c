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
    const auto flip = [](const std::optional<FlipResult>& f) {
        if (!f) return nlohmann::json();
        nlohmann::json one{{"mean", f->mean}, {"median", f->median}, {"p95", f->p95}, {"max", f->max}, {"pixels", f->pixels}};
        if (f->exposures.count > 0)
            one["exposures"] = {{"start", f->exposures.start}, {"stop", f->exposures.stop}, {"count", f->exposures.count}};
        return one;
    };
    nlohmann::json flipRecord{{"ldr", flip(metrics.ldrFlip)},
                              {"pixels_per_degree", FlipViewing{}.pixelsPerDegree()},
                              {"of", "R, G, B, linear, clamped to [0, 1] for LDR; Andersson et al. 2020, 2021"}};
    if (metrics.hdrFlip) flipRecord["hdr"] = flip(metrics.hdrFlip);
    if (!metrics.flipUnavailable.empty()) flipRecord["unavailable"] = metrics.flipUnavailable;
    return {{"all", values(metrics.all)},
            {"flip", std::move(flipRecord)},
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
