#include "libvri/render/diff_verdict.h"

#include <cstdio>

#include <nlohmann/json.hpp>

namespace vri {

namespace {

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

LimitCheck checkLimit(const ImageDiff& diff, std::size_t t, double allowedPercent, bool perPixel) {
    LimitCheck check{diff.thresholds.at(t), allowedPercent, 0, 0, "pixel-channels"};
    if (perPixel) {
        check.counted = "pixels";
        check.count = diff.pixelsAbove[t];
        check.percent = pixelPercent(diff, t);
    } else {
        for (const ChannelDiff& channel : diff.channels) check.count += channel.countAbove[t];
        check.percent = pixelChannelPercent(diff, t);
    }
    return check;
}

// "FAIL: 25% of pixel-channels above 1e-06 (allowed 0%)", or per pixel "... of pixels above 1e-06 in some channel ..."
std::string describe(const char* verdict, const LimitCheck& check) {
    return std::string(verdict) + ": " + format("%g", check.percent) + "% of " + check.counted + " above " +
           format("%g", check.limit) + (check.counted == "pixels" ? " in some channel" : "") + " (allowed " +
           format("%g", check.allowedPercent) + "%)";
}

nlohmann::json toJson(const LimitCheck& check) {
    return {{"threshold", check.limit},   {"allowed_percent", check.allowedPercent},
            {"count", check.count},       {"percent", check.percent},
            {"counted", check.counted},   {"exceeded", check.exceeded()}};
}

}  // namespace

double pixelChannelPercent(const ImageDiff& diff, std::size_t t) {
    std::uint64_t count = 0;
    for (const ChannelDiff& channel : diff.channels) count += channel.countAbove[t];
    return 100.0 * static_cast<double>(count) /
           (static_cast<double>(diff.pixels) * static_cast<double>(diff.channels.size()));
}

double pixelPercent(const ImageDiff& diff, std::size_t t) {
    return 100.0 * static_cast<double>(diff.pixelsAbove[t]) / static_cast<double>(diff.pixels);
}

DiffVerdict diffVerdict(const Image& a, const Image& b, const DiffLimits& limits, const PixelMask* mask) {
    const ImageDiff counts = compareImages(a, b, {limits.fail, limits.warn}, mask);
    DiffVerdict verdict;
    verdict.fail = checkLimit(counts, 0, limits.failPercent, limits.perPixel);
    verdict.warn = checkLimit(counts, 1, limits.warnPercent, limits.perPixel);
    if (verdict.fail.exceeded()) {
        verdict.code = kDiffFail;
        verdict.text = describe("FAIL", verdict.fail);
    } else if (verdict.warn.exceeded()) {
        verdict.code = kDiffWarn;
        verdict.text = describe("WARN", verdict.warn);
    }
    return verdict;
}

void addVerdict(nlohmann::json& record, const DiffVerdict& verdict) {
    record["verdict"] = verdict.code == kDiffPass ? "pass" : verdict.code == kDiffWarn ? "warn" : "fail";
    record["exit_code"] = verdict.code;
    record["fail"] = toJson(verdict.fail);
    record["warn"] = toJson(verdict.warn);
}

}  // namespace vri
