#pragma once
// The image metrics rendering papers and their reviewers read, beside vri's error statistics
// (image_compare.h): PSNR, SSIM, relative MSE and SMAPE, per channel and over all channels, over the
// pixels a mask keeps. The reference is the first image.
//  - PSNR = 10 log10(peak^2 / MSE) dB with peak 1, the top of a linear [0, 1] render (infinite for equal
//    images). Over all channels, the MSE of every pixel-channel.
//  - SSIM (Wang, Bovik, Sheikh and Simoncelli 2004): an 11 x 11 Gaussian window of sigma 1.5, normalised,
//    K1 = 0.01, K2 = 0.03, dynamic range L = 1, on each channel alone (linear values, no colour transform);
//    the mean of the SSIM map over the window positions that fit inside the image ("valid", as the authors'
//    MATLAB code) whose centre the mask keeps. Over all channels, the mean of the channels' SSIM. NaN for an
//    image smaller than the window.
//  - Relative MSE: the mean of (a - b)^2 / (a^2 + 0.01), a the reference (Rousselle et al.'s form).
//  - SMAPE: the mean of |a - b| / (|a| + |b| + 0.01).
//  - FLIP (flip.h): LDR-FLIP of the R, G and B channels (linear, clamped to [0, 1]) at the papers' viewing
//    distance, its mean, median, 95th percentile and largest error over the mask's pixels; HDR-FLIP on
//    request, its exposures from the reference's pixels that either image hits (alpha > 0, where the last
//    channel is A: the black background would put the median luminance, and so the last exposure, at 0).
//    Not computed for images without R, G and B, or with a NaN or infinity in them; `flipUnavailable` then
//    says why (for HDR-FLIP alone: "HDR-FLIP: ..." when its exposures cannot be computed).
// Errors follow image_compare.h: a NaN against a number is an infinite error.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libvri/core/flip.h"
#include "libvri/core/image.h"
#include "libvri/core/pixel_mask.h"

namespace vri {

struct MetricValues {
    double psnr = 0, ssim = 0, relMse = 0, smape = 0;
};

struct ImageMetrics {
    std::vector<std::string> channelNames;
    std::vector<MetricValues> channels;  // in the images' channel order
    MetricValues all;                    // over every channel
    std::uint64_t pixels = 0;            // the pixels counted
    std::uint64_t ssimWindows = 0;       // the SSIM window positions counted
    std::optional<FlipResult> ldrFlip, hdrFlip;  // their error maps left empty
    std::string flipUnavailable;                 // why FLIP is missing, "" when it is not
};

inline constexpr double kPsnrPeak = 1.0;
inline constexpr double kRelativeEpsilon = 0.01;  // relative MSE's and SMAPE's guard against division by 0

// Throws vri::Error when the images differ in shape or the mask is not theirs.
ImageMetrics imageMetrics(const Image& reference, const Image& test, const PixelMask* mask = nullptr,
                          bool withHdrFlip = false);

}  // namespace vri
