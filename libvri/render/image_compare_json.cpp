#include "libvri/render/image_compare_json.h"

#include <nlohmann/json.hpp>

namespace vri {

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
            {"pixels_counted", "all"},
            {"thresholds", diff.thresholds},
            {"channels", std::move(channels)}};
}

}  // namespace vri
