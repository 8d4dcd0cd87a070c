#pragma once
// vri-diff's verdict (idiff's, exit codes one up): fail when more than --failpercent of the pixel-channels
// (or, per pixel, of the pixels with any channel) are above --fail, else warn likewise; shared with the
// Python module's compare(), so that both say the same of the same images.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "libvri/core/image.h"
#include "libvri/core/image_compare.h"

namespace vri {

// idiff's ErrOK, ErrWarn, ErrFail and ErrDifferentSize are 0 to 3, and its ErrFile 4; here the verdicts
// are idiff's plus one, so that a warning never reads as a failure to read or write a file, which is
// exit 1 as in every tool.
inline constexpr int kDiffPass = 0;
inline constexpr int kDiffWarn = 2;
inline constexpr int kDiffFail = 3;
inline constexpr int kDiffDifferentShape = 4;

struct DiffLimits {
    double fail = 1e-6, failPercent = 0;
    double warn = 1e-6, warnPercent = 0;
    bool perPixel = false;  // count pixels with any channel above, as idiff does, not pixel-channels
};

// How many pixel-channels (or pixels) have an error above a limit, and whether that is more than allowed.
struct LimitCheck {
    double limit = 0;
    double allowedPercent = 0;
    std::uint64_t count = 0;
    double percent = 0;
    std::string counted = "pixel-channels";  // or "pixels"
    bool exceeded() const { return percent > allowedPercent; }
};

struct DiffVerdict {
    int code = kDiffPass;
    std::string text = "PASS";  // "FAIL: 25% of pixel-channels above 1e-06 (allowed 0%)"
    LimitCheck fail, warn;
};

// The shares of a comparison above its threshold number `t`: of all pixel-channels, and of the pixels
// with some channel above (idiff's count).
double pixelChannelPercent(const ImageDiff& diff, std::size_t t);
double pixelPercent(const ImageDiff& diff, std::size_t t);

// Throws as requireSameShape. Over the pixels `mask` keeps (all when null).
DiffVerdict diffVerdict(const Image& a, const Image& b, const DiffLimits& limits, const PixelMask* mask = nullptr);

// Adds "verdict" (pass, warn, fail), "exit_code", "fail" and "warn" ({threshold, allowed_percent, count,
// percent, counted, exceeded}) to a comparison's record (image_compare_json.h).
void addVerdict(nlohmann::json& record, const DiffVerdict& verdict);

}  // namespace vri
