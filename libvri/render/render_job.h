#pragma once
// One render asked for, from request to image, bounds and provenance record: the flow vri-render,
// vri-reference and Python's vri.render share (in the spirit of GDAL's gdal_translate_lib.cpp, which
// its binary and its Python binding both call). It checks the request against the scene, picks the
// backend, searches the exact method's tolerance for --max-error, renders frames, and then finds
// non-finite and out-of-range pixels, clamps, and writes the record a stats file holds. It neither
// parses a command line nor prints: its warnings come back as text.
//
//     RenderJob job(request, std::move(setup), {.tool = "vri-render", .command = commandLine(argc, argv)});
//     job.searchTolerance();                          // --max-error, when asked
//     RenderFrame first = job.frame();                // as often as the timing asks; frames are equal
//     RenderResult result = job.finish(std::move(first), frameTimingRecord(0, {first.seconds}));
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/core/camera.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/image.h"
#include "libvri/core/render_option_table.h"
#include "libvri/io/image_io.h"
#include "libvri/render/max_error_search.h"
#include "libvri/render/render_backend.h"
#include "libvri/render/scene_setup.h"

namespace vri {

// Who asks, for the record, and what the caller wants beyond the image.
struct RenderJobContext {
    std::string tool;             // the record's "tool": "vri-render", "vri-reference", "python"
    nlohmann::json command;       // the record's "command": commandLine()'s {"argv", "shell"}, or Python's call
    bool wantBounds = false;      // the exact method's per-pixel bound image (--error-image)
    bool allowNonFinite = false;  // keep an image with NaN or infinite pixels (a warning) instead of refusing it
    std::string allowNonFiniteName = "--allow-nonfinite";  // how the caller spells that, for the refusal
};

// One computation of the image.
struct RenderFrame {
    Image image;
    std::optional<Image> bounds;  // the exact method's per-pixel error bounds, when RenderJobContext asks
    RenderStats stats;            // the exact method: only the non-finite count (it has stats of its own)
    std::optional<ExactReferenceStats> exactStats;
    double seconds = 0.0;  // the frame's own work (the method's stats' seconds)
};

struct RenderResult {
    Image image;  // clamped when the request asks for it
    std::optional<Image> bounds;
    RenderStats stats;
    std::optional<ExactReferenceStats> exactStats;
    nlohmann::json record;              // the provenance record a stats file holds
    ImageMetadata metadata;             // what the EXR and PNG outputs carry (vri:command, vri:options, ...)
    std::vector<std::string> warnings;  // one line each, for stderr (the record keeps those a reader needs)
};

class RenderJob {
public:
    // Checks what needs the scene (a sparse volume is for the CPU's scalar path only) and opens the backend
    // (Vulkan: the device); throws vri::Error naming the option at fault.
    RenderJob(RenderRequest request, SceneSetup setup, RenderJobContext context);

    // --max-error: searches the exact method's tolerance (max_error_search.h); its accepted render becomes
    // the next frame. Nothing to do without --max-error.
    void searchTolerance();
    // Renders one frame: the image the request asks for (with --frames N, the mean of N jittered frames).
    RenderFrame frame();
    // An untimed frame before the timed ones: as frame(), but one jittered frame where --frames asks for
    // several; it warms what a frame of them warms (caches, threads, clocks) at a frame's price.
    RenderFrame warmUpFrame();
    // The image and its record from the first frame, with the timing record of every frame
    // (frameTimingRecord()); throws vri::Error on non-finite pixels unless the context allows them.
    RenderResult finish(RenderFrame first, nlohmann::json timing);

    const RenderRequest& request() const { return request_; }
    const SceneSetup& setup() const { return setup_; }

private:
    RenderFrame methodFrame(const RenderOptions& options);  // a frame of a method other than exact

    RenderRequest request_;
    SceneSetup setup_;
    RenderJobContext context_;
    Camera camera_;
    RenderBackend backend_;
    std::optional<MaxErrorSearch> search_;
};

// The head of every render's provenance record: what was run ("tool", "command"), when, by which build on
// which machine, from which inputs, and the scene, transfer function, camera and settings it rendered.
nlohmann::json provenanceRecord(const std::string& tool, const nlohmann::json& command, const SceneSetup& setup,
                                const RenderRequest& request);

// What else ran while a render timed its frames (util/cpu_load.h): other processes' cores beside the
// render's threads, on the machine's cores. Overloaded, when together they exceed the cores by more than half
// a core, the times are inflated.
struct TimingLoad {
    double otherCores = 0;
    int threads = 1, cores = 1;
    bool overloaded() const { return otherCores + threads > cores + 0.5; }
};

// The record of the frames a render timed: {"warm_up_frames", "repeats", "wall_seconds", "median_wall_seconds",
// "median_ci": {"low", "high", "coverage"}, "load": {"other_cores", "threads", "cores", "overloaded"} or null}.
// The median's interval is that of the frames' order statistics (x_(k), x_(n+1-k)) with the largest k whose
// coverage, 1 - 2 P(Binomial(n, 1/2) < k), is at least 0.95, else k = 1 and its coverage (75 % for 3 frames).
nlohmann::json frameTimingRecord(int warmUpFrames, const std::vector<double>& wallSeconds,
                                 const std::optional<TimingLoad>& load = std::nullopt);

// A run's stats record's timing.load, the reader of frameTimingRecord's: nullopt where the record has none
// (an outside renderer's, frames too short to measure, stats of an older vri).
std::optional<TimingLoad> timingLoadOf(const nlohmann::json& stats);

// The interval above as (low, high, coverage).
struct MedianInterval {
    double low = 0, high = 0, coverage = 0;
};
MedianInterval medianInterval(std::vector<double> values);
nlohmann::json medianIntervalRecord(const std::vector<double>& values);  // {"low", "high", "coverage"}

}  // namespace vri
