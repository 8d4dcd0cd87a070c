// vri-diff: per-channel error statistics between two images, with a pass/warn/fail verdict whose
// exit codes follow OpenImageIO's idiff, one up: 1 stays every tool's failure (README, "Exit codes").
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdint>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/core/heat_map.h"
#include "libvri/core/image_compare.h"
#include "libvri/core/image_metrics.h"
#include "libvri/core/nonfinite_pixels.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/io/image_io.h"
#include "libvri/io/provenance.h"
#include "libvri/render/diff_verdict.h"
#include "libvri/render/image_compare_json.h"
#include "libvri/render/pixel_mask_for.h"
#include "libvri/render/tool_flags.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/format.h"
#include "libvri/util/json_file.h"
#include "libvri/util/parse.h"

namespace {

constexpr const char* kTool = "vri-diff";


struct Options {
    std::string a, b;
    std::vector<double> thresholds = vri::kDefaultThresholds;
    std::string json, diffImage, histogram, layers;
    std::string channels;  // --channels: names, comma separated; empty: all
    std::string mask = "all";  // --mask: all, hit, alpha>T or a mask image
    std::string heatScale = "linear";  // --heat-scale: linear or log[:DECADES]
    std::string heatTop = "max";       // --heat-top: max or pN
    std::string title;                 // --title: the heat map's; empty: what is compared, the value, the scale
    bool signedMaps = false;           // --heat-signed
    bool hdrFlip = false;              // --hdr-flip
    bool heatLog = false;
    int decades = 3;
    double diffScale = 1.0;
    std::vector<std::string> scaleOver;  // a PNG heat map's scale: the largest |A - X| over B and these
    std::string scaleFrom;               // or the scale another vri-diff's JSON records (heat_map.top)
    std::vector<double> histogramRange{1e-6, 1.0};
    int binsPerDecade = 5;
    vri::DiffLimits limits;
};

bool isPng(const std::string& path) { return vri::lowercaseExtension(path) == ".png"; }

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// Columns of a fixed width; the trailing blanks of a row are dropped.
class Row {
public:
    Row& cell(const std::string& text, std::size_t width) {
        text_ += text;
        text_.resize(std::max(text_.size() + 1, column_ += width), ' ');
        return *this;
    }
    std::string str() const { return text_.substr(0, text_.find_last_not_of(' ') + 1); }

private:
    std::string text_;
    std::size_t column_ = 0;
};

void printSummary(const Options& options, const vri::ImageDiff& diff, const vri::ImageMetrics& metrics,
                  const std::string& verdict) {
    std::cout << options.a << " vs " << options.b << ": " << diff.width << "x" << diff.height << ", "
              << diff.channels.size() << " channels, " << diff.pixels << " pixels counted ("
              << (diff.mask == vri::kAllPixels ? std::string("all") : diff.mask) << ")\n";
    Row header;
    header.cell("channel", 8).cell("max", 13).cell("at (x,y)", 12).cell("mean", 13).cell("RMSE", 13);
    for (double t : diff.thresholds) header.cell("% > " + format("%g", t), 12);  // of the channel's pixels
    std::cout << header.str() << '\n';
    for (const vri::ChannelDiff& channel : diff.channels) {
        Row row;
        row.cell(channel.name, 8)
            .cell(format("%.6g", channel.maxAbs), 13)
            .cell("(" + std::to_string(channel.maxX) + "," + std::to_string(channel.maxY) + ")", 12)
            .cell(format("%.6g", channel.meanAbs), 13)
            .cell(format("%.6g", channel.rmse), 13);
        for (double percent : channel.percentAbove) row.cell(format("%.4f", percent), 12);
        std::cout << row.str() << '\n';
    }
    // A channel's % is of its pixels; over the channels two counts differ, and each says which it is.
    constexpr std::size_t kLabelWidth = 8 + 13 + 12 + 13 + 13;
    Row pixelChannels, pixels;
    pixelChannels.cell("all channels: % of pixel-channels (pixels x channels)", kLabelWidth);
    pixels.cell("any channel: % of pixels (as idiff counts, --per-pixel)", kLabelWidth);
    for (std::size_t t = 0; t < diff.thresholds.size(); ++t) {
        pixelChannels.cell(format("%.4f", pixelChannelPercent(diff, t)), 12);
        pixels.cell(format("%.4f", pixelPercent(diff, t)), 12);
    }
    std::cout << pixelChannels.str() << '\n' << pixels.str() << '\n';
    const auto metric = [](const char* pattern, double x) { return std::isfinite(x) ? format(pattern, x) : "n/a"; };
    std::cout << "PSNR " << (metrics.all.psnr == INFINITY ? std::string("inf") : metric("%.2f", metrics.all.psnr))
              << " dB (peak 1), SSIM " << metric("%.4f", metrics.all.ssim) << " (11x11 Gaussian, sigma 1.5), relMSE "
              << metric("%.4g", metrics.all.relMse) << ", SMAPE " << metric("%.4g", metrics.all.smape)
              << " (all channels)\n";
    for (const auto& [name, flip] : {std::pair{"LDR-FLIP", &metrics.ldrFlip}, std::pair{"HDR-FLIP", &metrics.hdrFlip}})
        if (*flip)
            std::cout << name << " mean " << format("%.4f", (*flip)->mean) << ", median " << format("%.4f", (*flip)->median)
                      << ", 95th percentile " << format("%.4f", (*flip)->p95) << ", max " << format("%.4f", (*flip)->max)
                      << " (R, G, B at " << format("%.1f", vri::FlipViewing{}.pixelsPerDegree()) << " pixels per degree)\n";
    if (!metrics.flipUnavailable.empty()) std::cout << metrics.flipUnavailable << '\n';
    std::cout << verdict << '\n';
}

// A heat map's default title: "b vs a: max |A-B| over channels, linear to 0.045" (the files' stems), what a reader of the
// PNG alone needs to know.
std::string heatMapTitle(const Options& options, double top, const std::string& topFrom) {
    const auto stem = [](const std::string& path) { return std::filesystem::path(path).stem().string(); };
    std::string title = stem(options.b) + " vs " + stem(options.a) + ": ";
    if (options.signedMaps)
        return title + "B - A per channel, -" + format("%.3g", top) + " to " + format("%.3g", top) +
               (topFrom.starts_with("p") ? " (" + topFrom + ")" : "");
    title += "max |A-B| over channels, ";
    if (options.heatLog) title += "log, " + std::to_string(options.decades) + " decades to ";
    else title += "linear to ";
    title += format("%.3g", top);
    if (topFrom.starts_with("p")) title += " (" + topFrom + ")";
    if (!options.scaleOver.empty() || !options.scaleFrom.empty()) title += ", one scale for the set";
    return title;
}

const CLI::Validator kNonNegative = vri::numberAbove(0.0, true);
const CLI::Validator kPositive = vri::numberAbove(0.0, false);

// A failed comparison of two images of which one is upside down says so: B flipped vertically much
// nearer A is a renderer that writes row 0 at the bottom, not a render that is wrong everywhere.
void flipHint(const vri::Image& a, const vri::Image& b, const vri::ImageDiff& diff) {
    const auto rmse = [](const vri::ImageDiff& d) {
        double worst = 0;
        for (const vri::ChannelDiff& c : d.channels) worst = std::max(worst, c.rmse);
        return worst;
    };
    const double upright = rmse(diff), flipped = rmse(vri::compareImages(a, vri::flippedVertically(b), {}));
    if (flipped < 0.5 * upright)
        std::cerr << kTool << ": hint: B flipped vertically is " << upright / flipped << " times nearer A (RMSE "
                  << flipped << " against " << upright << "): is B's row 0 at the bottom?\n";
}

// The one-line message of vri::guardedMain, with the exit code that names this kind of failure.
int exitWith(int code, const std::exception& error) {
    std::cerr << kTool << ": error: " << vri::printable(error.what()) << '\n';
    return code;
}

int run(int argc, char** argv) {
    Options options;
    CLI::App app{"Compares two images channel by channel: largest, mean and RMS absolute error, and the share of "
                 "pixels whose error is strictly above each threshold. Every pixel counts as a ray, background "
                 "included.",
                 kTool};
    app.add_option("A", options.a, "first image (reference), any format OpenImageIO reads")->required();
    app.add_option("B", options.b, "second image, same size and channel count")->required();
    app.add_option("--channels", options.channels,
                   "compare only these channels, by name, comma separated (R,G,B for an image without alpha)");
    vri::addListOption(app, vri::diff_flag::threshold, options.thresholds,
                       "error thresholds to report, comma separated", kNonNegative);
    app.add_option(vri::diff_flag::json, options.json,
                   "write all statistics as JSON to FILE; '-' prints them on stdout "
                   "instead of the summary");
    auto* diffImage = app.add_option(
        vri::diff_flag::diffImage, options.diffImage,
        "write the difference image: .exr the per-channel |A - B| (exact); .png a heat map of the largest |A - B| over "
        "the channels (viridis, dark blue 0 to yellow at the top of the scale) with a colour bar below it, numbered "
        "at quarters of the scale; the JSON gives the scale (heat_map.top)");
    auto* diffScale = app.add_option(vri::diff_flag::diffScale, options.diffScale,
                                     "EXR: multiply the difference image by K; PNG: the heat map's scale "
                                     "runs to 1/K (default: to the largest difference)")
                          ->check(kPositive)
                          ->needs(diffImage)
                          ->capture_default_str();
    app.add_option(
           vri::diff_flag::scaleOver, options.scaleOver,
           "IMAGE (repeatable): a PNG heat map's scale runs to the largest |A - X| over B and each such image X "
           "(A's size and channels): one scale for a set of comparisons against A, as the other comparisons "
           "of the set give it")
        ->allow_extra_args(false)
        ->needs(diffImage)
        ->excludes(diffScale);
    app.add_option(vri::diff_flag::heatScale, options.heatScale,
                   "a PNG heat map's colours: linear from 0 to the top, or log: the DECADES decades below the top "
                   "(log is log:3), for a set whose errors span orders of magnitude")
        ->needs(diffImage)
        ->capture_default_str();
    app.add_option(vri::diff_flag::heatTop, options.heatTop,
                   "a PNG heat map's top when --diff-scale and --scale-from do not set it: max, the largest error of B "
                   "and the --scale-over images, or pN, the Nth percentile of their pixels' errors (those --mask keeps "
                   "and that are not 0), so that one outlier cannot darken every map; pixels above it show in magenta")
        ->needs(diffImage)
        ->excludes(diffScale)
        ->capture_default_str();
    app.add_flag(vri::diff_flag::heatSigned, options.signedMaps,
                 "a PNG shows B - A per channel, side by side, blue below 0, red above, on one linear scale")
        ->needs(diffImage)
        ->excludes(vri::diff_flag::heatScale);
    app.add_option("--title", options.title,
                   "the title line above a PNG heat map (default: B vs A, the value shown and its scale)")
        ->needs(diffImage);
    app.add_option(vri::diff_flag::scaleFrom, options.scaleFrom,
                   "JSON: a PNG heat map's scale is the one another vri-diff's --json recorded (its heat_map.top): the "
                   "set's scale computed once, by the comparison of the set that takes --scale-over")
        ->needs(diffImage)
        ->excludes(diffScale)
        ->excludes(vri::diff_flag::scaleOver);
    app.add_flag("--hdr-flip", options.hdrFlip,
                 "also HDR-FLIP (tone mapped over the exposures of the reference's hit pixels); LDR-FLIP is always "
                 "computed for R, G, B");
    app.add_option("--layers", options.layers,
                   "write FILE.exr with three layers, reference.*, test.* and error.* (|A - B|), to flip between in tev "
                   "or another EXR viewer");
    app.add_option(vri::diff_flag::mask, options.mask,
                   "which pixels every statistic counts: all (default), hit (alpha > 0 in either image), alpha>T, "
                   "or a mask image (its first channel's non-zero pixels)")
        ->capture_default_str();
    app.add_option(vri::diff_flag::histogram, options.histogram,
                   "write per-channel error histograms as CSV "
                   "(bin_lo,bin_hi,R,G,B,A; bins (lo, hi], plus a zero bin)");
    vri::addListOption(app, "--histogram-range", options.histogramRange, "LO,HI: logarithmic histogram bins span this",
                       std::nullopt, 2);
    app.add_option("--bins-per-decade", options.binsPerDecade, "histogram bins per factor of ten")
        ->check(kPositive)
        ->capture_default_str();
    app.add_option("--fail", options.limits.fail, "failure threshold on the absolute error")
        ->check(kNonNegative)
        ->capture_default_str();
    app.add_flag("--per-pixel", options.limits.perPixel,
                 "--failpercent and --warnpercent count pixels with any channel above the limit, as OpenImageIO's "
                 "idiff does, instead of pixel-channels (pixels x channels)");
    app.add_option(vri::diff_flag::failPercent, options.limits.failPercent,
                   "fail when more than this % of pixel-channels is above --fail")
        ->check(vri::numberRange(0.0, 100.0))
        ->capture_default_str();
    app.add_option("--warn", options.limits.warn, "warning threshold on the absolute error")
        ->check(kNonNegative)
        ->capture_default_str();
    app.add_option(vri::diff_flag::warnPercent, options.limits.warnPercent,
                   "warn when more than this % of pixel-channels is above --warn")
        ->check(vri::numberRange(0.0, 100.0))
        ->capture_default_str();
    app.footer(
        "Exit codes (idiff's, one up): 0 pass, 2 warning, 3 failure, 4 images differ in size or channel count;\n"
        "1 a file is missing or unreadable (or an output cannot be written), 64 bad arguments.\n"
        "Percentages of --failpercent/--warnpercent are over all pixel-channels (pixels x channels), or with\n"
        "--per-pixel over pixels, a pixel counting when any channel is above, as idiff counts (more of them).\n"
        "\n"
        "Examples:\n"
        "  vri-diff reference.exr render.exr\n"
        "      summary on stdout, fails if any pixel-channel differs by more than 1e-6\n"
        "  vri-diff ref.exr riemann_h0.5.exr --threshold 0.01,0.005,0.001 --json stats.json \\\n"
        "      --histogram hist.csv --diff-image err.exr --fail 0.01 --failpercent 1\n"
        "      Paper B's table numbers and histograms; fails if more than 1% of pixel-channels exceed 0.01\n"
        "  vri-diff a.exr b.exr --json - | jq '.channels[].max_abs'\n"
        "      statistics as JSON on stdout only");
    if (auto exitCode = vri::parseArguments(app, "vri-diff", argc, argv)) return *exitCode;

    std::vector<double> histogramEdges;
    if (!options.histogram.empty()) {
        try {
            histogramEdges = vri::logBinEdges(options.histogramRange[0], options.histogramRange[1], options.binsPerDecade);
        } catch (const vri::Error& e) {
            return exitWith(vri::kExitUsage, e);
        }
    }

    for (const char* output :
         {vri::diff_flag::json, vri::diff_flag::diffImage, vri::diff_flag::histogram, "--layers", "--title"})
        if (app.count(output) > 0 && app[output]->as<std::string>().empty())
            return exitWith(vri::kExitUsage, vri::Error(std::string(output) + ": expected " +
                                                        (std::string(output) == "--title" ? "a title" : "a file name") +
                                                        ", got ''"));
    if (diffScale->count() > 0 && isPng(options.diffImage) && !std::isfinite(1.0 / options.diffScale))
        return exitWith(vri::kExitUsage,
                        vri::Error("--diff-scale: " + vri::exactNumber(options.diffScale) +
                                   " puts the heat map's top at 1/K, which is not a finite number"));
    for (const auto& [option, given] : {std::pair{vri::diff_flag::scaleOver, !options.scaleOver.empty()},
                                        std::pair{vri::diff_flag::scaleFrom, !options.scaleFrom.empty()}})
        if (given && !isPng(options.diffImage))
            return exitWith(vri::kExitUsage, vri::Error(std::string(option) +
                                                        " sets the scale of a PNG heat map; --diff-image '" +
                                                        options.diffImage + "' is not a .png"));
    if (options.heatScale != "linear") {
        const std::optional<int> decades = vri::heatScaleDecades(options.heatScale);
        if (!decades)
            return exitWith(vri::kExitUsage, vri::Error("--heat-scale: expected linear, log or log:N with N decades "
                                                        "in 1..12, got '" + options.heatScale + "'"));
        if (!isPng(options.diffImage))
            return exitWith(vri::kExitUsage, vri::Error("--heat-scale sets a PNG heat map's colours; --diff-image '" +
                                                        options.diffImage + "' is not a .png"));
        options.heatLog = true;
        options.decades = *decades;
    }
    if (!options.layers.empty() && vri::lowercaseExtension(options.layers) != ".exr")
        return exitWith(vri::kExitUsage, vri::Error("--layers: expected a .exr file (only OpenEXR keeps layers), got '" +
                                                    options.layers + "'"));
    const std::optional<double> percentile = vri::heatTopPercentile(options.heatTop);
    if (!percentile)
        return exitWith(vri::kExitUsage, vri::Error("--heat-top: expected max or pN with N in (0, 100], got '" +
                                                    options.heatTop + "'"));
    for (const auto& [option, given] :
         {std::pair{vri::diff_flag::heatTop, options.heatTop != "max"},
          std::pair{vri::diff_flag::heatSigned, options.signedMaps}, std::pair{"--title", !options.title.empty()}})
        if (given && !isPng(options.diffImage))
            return exitWith(vri::kExitUsage, vri::Error(std::string(option) + " is a PNG heat map's; --diff-image '" +
                                                        options.diffImage + "' is not a .png"));
    const std::vector<vri::OutputArgument> outputs{{vri::diff_flag::json, options.json},
                                                   {vri::diff_flag::diffImage, options.diffImage},
                                                   {vri::diff_flag::histogram, options.histogram},
                                                   {"--layers", options.layers}};
    vri::requireDistinctOutputs(outputs);
    std::vector<vri::InputArgument> inputs{{"A", options.a}, {"B", options.b}};
    for (const std::string& x : options.scaleOver) inputs.push_back({vri::diff_flag::scaleOver, x});
    if (!options.scaleFrom.empty()) inputs.push_back({vri::diff_flag::scaleFrom, options.scaleFrom});
    vri::requireOutputsApartFromInputs(outputs, inputs);
    if (!options.json.empty()) vri::requireUtf8Arguments(argc, argv);
    // A file that cannot be read or written is guardedMain's failure, exit 1.
    vri::Image a = vri::readImage(options.a);
    vri::Image b = vri::readImage(options.b);
    if (!options.channels.empty()) {
        const std::vector<std::string> names = vri::parseWordList(options.channels, "--channels");
        a = vri::selectChannels(a, names, options.a);
        b = vri::selectChannels(b, names, options.b);
    }
    try {
        vri::requireSameShape(a, b);
    } catch (const vri::Error& e) {
        return exitWith(vri::kDiffDifferentShape, e);
    }

    vri::MaskSpec spec;
    try {
        spec = vri::parseMaskSpec(options.mask);
    } catch (const vri::Error& e) {
        return exitWith(vri::kExitUsage, vri::Error("--mask: " + std::string(e.what())));
    }
    vri::PixelMask mask;
    try {
        mask = vri::pixelMaskFor(spec, a, b);
    } catch (const vri::Error& e) {
        return exitWith(vri::kExitError, vri::Error("--mask " + options.mask + ": " + e.what()));
    }
    // Non-finite values are compared by vri's rule (image_compare.h), which the reader should know was applied.
    const vri::NonFinitePixels nonfiniteA = vri::findNonFinitePixels(a), nonfiniteB = vri::findNonFinitePixels(b);
    for (const auto& [name, found] : {std::pair{"A", &nonfiniteA}, std::pair{"B", &nonfiniteB}})
        if (found->count > 0)
            std::cerr << kTool << ": warning: " << name << ": " << found->describe()
                      << "; each against a number counts as an infinite error, equal ones as none\n";
    const vri::ImageDiff diff = vri::compareImages(a, b, options.thresholds, &mask);
    const vri::ImageMetrics metrics = vri::imageMetrics(a, b, &mask, options.hdrFlip);
    const vri::DiffVerdict verdict = vri::diffVerdict(a, b, options.limits, &mask);

    std::optional<double> heatTop;  // the top of a PNG heat map's scale
    std::string topFrom;            // what set it: --diff-scale, max or pN (of this set, or of --scale-from's)
    vri::OutputSet files;
    if (!options.diffImage.empty() && isPng(options.diffImage)) {
        std::vector<vri::Image> others;  // --scale-over's images
        for (const std::string& path : options.scaleOver) {
            others.push_back(vri::readImage(path));
            try {
                vri::requireSameShape(a, others.back());
            } catch (const vri::Error& e) {
                return exitWith(vri::kDiffDifferentShape, vri::Error("--scale-over " + path + ": " + e.what()));
            }
        }
        if (diffScale->count() > 0) {
            heatTop = 1.0 / options.diffScale;
            topFrom = vri::diff_flag::diffScale;
        } else if (!options.scaleFrom.empty()) {  // the set's top, and the rule that set it
            try {
                const nlohmann::json other = vri::readJsonFile(options.scaleFrom);
                vri::readingJsonOf(options.scaleFrom, [&] {
                    heatTop = other.at("heat_map").at("top").get<double>();
                    topFrom = other.at("heat_map").value("top_from", "max");
                });
            } catch (const vri::Error& e) {
                return exitWith(vri::kExitError, vri::Error("--scale-from " + std::string(e.what())));
            }
        } else {
            std::vector<const vri::Image*> set{&b};
            for (const vri::Image& x : others) set.push_back(&x);
            heatTop = vri::heatMapTop(a, set, *percentile, &mask);
            topFrom = options.heatTop;
        }
        if (!(*heatTop > 0) || !std::isfinite(*heatTop)) {  // equal images, or an infinite error
            heatTop = 1.0;
            topFrom = "1: no finite error above 0 to scale by";
        }
        const std::string title = !options.title.empty() ? options.title : heatMapTitle(options, *heatTop, topFrom);
        files.add(options.diffImage,
                  vri::encodePng(options.diffImage,
                                 options.signedMaps ? vri::signedHeatMapImage(a, b, *heatTop, title)
                                                    : vri::heatMapImage(a, b, {*heatTop, options.heatLog, options.decades}, title)));
    } else if (!options.diffImage.empty()) {
        files.add(options.diffImage, vri::encodeImage(options.diffImage, vri::differenceImage(a, b, options.diffScale)));
    }
    if (!options.layers.empty()) files.add(options.layers, vri::encodeImage(options.layers, vri::comparisonLayers(a, b)));
    if (!options.histogram.empty())
        files.add(options.histogram, vri::toCsv(vri::errorHistogram(a, b, histogramEdges, &mask)));
    if (!options.json.empty()) {
        nlohmann::json json = vri::toJson(diff);
        json["metrics"] = vri::toJson(metrics);
        json["nonfinite_pixels"] = {{"a", nonfiniteA.count}, {"b", nonfiniteB.count}};
        json["a"] = options.a;
        json["b"] = options.b;
        vri::addVerdict(json, verdict);
        json["command"] = vri::commandLine(argc, argv);
        if (heatTop)
            json["heat_map"] = {{"file", options.diffImage},
                                {"value", options.signedMaps ? "B - A per channel" : "largest |A - B| over the channels"},
                                {"colormap", options.signedMaps ? "cool-warm" : "viridis"},
                                {"top", *heatTop},
                                {"scale", options.heatLog ? "log" : "linear"},
                                {"top_from", topFrom},
                                {"clipped", options.signedMaps ? "black: beyond -top or +top" : "magenta: above the top"}};
        if (heatTop && options.heatLog) {
            json["heat_map"]["decades"] = options.decades;
            json["heat_map"]["bottom"] = *heatTop * std::pow(10.0, -options.decades);
        }
        if (heatTop && !options.scaleOver.empty()) json["heat_map"]["scale_over"] = options.scaleOver;
        if (heatTop && !options.scaleFrom.empty()) json["heat_map"]["scale_from"] = options.scaleFrom;
        files.add(options.json, json.dump(2) + "\n");
    }
    files.write();
    // The summary goes to standard output unless an output does (it would run into that output).
    if (std::none_of(outputs.begin(), outputs.end(), [](const vri::OutputArgument& o) { return o.path == "-"; }))
        printSummary(options, diff, metrics, verdict.text);
    if (verdict.code != vri::kExitOk) flipHint(a, b, diff);
    return verdict.code;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
