// vri-render: renders one image of a volume or analytic field with the CPU raycaster or the Vulkan backend.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "common/cli.h"
#include "common/exact_reference_json.h"
#include "common/frame_timing.h"
#include "common/nonfinite_option.h"
#include "common/preview_options.h"
#include "common/render_json.h"
#include "common/scene_options.h"
#include "vri/core/cpu_renderer.h"
#include "vri/core/exact_reference.h"
#include "vri/io/adaptive_log_csv.h"
#include "vri/io/image_io.h"
#include "vri/io/provenance.h"
#include "vri/util/atomic_file.h"
#include "vri/vulkan/vulkan_renderer.h"

namespace fs = std::filesystem;

namespace {

// --list-devices: one line per Vulkan device, "INDEX<TAB>NAME<TAB>TYPE<TAB>API VERSION".
int listDevices() {
    const std::vector<vri::VulkanDeviceInfo> devices = vri::VulkanRenderer::listDevices();
    if (devices.empty()) {
        std::cerr << "vri-render: error: no Vulkan device found\n";
        return vri::kExitError;
    }
    for (const vri::VulkanDeviceInfo& d : devices)
        std::cout << d.index << '\t' << d.name << '\t' << d.type << '\t' << d.apiVersion << '\n';
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Render a volume (or an analytic field) with the CPU raycaster or on a Vulkan device: float RGBA "
                 "OpenEXR, an optional 8-bit PNG preview and a JSON stats file."};
    app.footer(R"(Examples:
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml \
             --size 800x600 --step 0.5 -o bonsai.exr --png bonsai.png --stats bonsai.json
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --method coupled \
             --tolerance 0.01 --log-ray 400,300 --log ray.csv -o coupled.exr --stats coupled.json
  vri-render --field linear --field-dims 5,5,5 --convention node --tf experiments/tf/paper-a-linear.yaml \
             --placement entry-exit-corner --rate 1 --eye -9,0,0 --target 0,0,0 --fov 30 -o corner.exr

  vri-render --backend vulkan --device llvmpipe --volume bonsai_256x256x256_uint8.raw \
             --tf experiments/tf/paper-b-bonsai.yaml --method coupled -o coupled-vk.exr
  vri-render --backend vulkan --interpolation sampler --volume bonsai_256x256x256_uint8.raw \
             --tf experiments/tf/paper-b-bonsai.yaml --step 0.1 -o riemann-sampler.exr
  vri-render --list-devices
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --method exact \
             --tolerance 1e-7 -o exact.exr --stats exact.json

exact: vri-reference's method (pieces on which the field is a cubic, Gauss-Kronrod quadrature), in double
on the CPU; --tolerance is the error allowed per transfer-function piece (default 1e-7 for exact) and the
stats give the per-pixel error bound ("error_bound": max and mean per channel).
Steps are in voxels: --step h is --rate 1/h. Colours are in the TF's units, alpha = 1 - transparency
(Simpson methods: alpha = the integral of extinction times transparency, paper B's fourth channel).

Limits, checked before any work: a volume or image may take at most 16 GiB (set VRI_MAX_BYTES to a byte
count to change it); a ray at most 1e9 samples (--step, --rate) or, for the Simpson methods, 1e9 steps of
h_min (2^22 in float precision, where a shorter step would no longer advance the ray).)");

    std::string output, pngPath, statsPath, logPath, logRay, hMax = "2";
    vri::SceneOptions sceneOptions;
    std::string method = "riemann", placement = "entry", precision = "double", backend = "cpu", device;
    std::string interpolation = "shader", simd = "on";
    bool listDevicesFlag = false;
    double rate = 0.0, step = 0.0;
    std::string ert = "0";
    vri::PreviewOptions preview;
    vri::NonFiniteOption nonfinite;
    bool noSkip = false, quiet = false;
    vri::FrameTiming timing;
    vri::AdaptiveParameters adaptive;
    std::string accepted{vri::acceptedValueName(adaptive.accepted)};

    sceneOptions.addTo(app);
    app.add_option("--method", method, "riemann (paper A eq. 5), composite (opacity-corrected), simpson (uniform "
                                       "steps of --step), coupled or decoupled (paper B's adaptive Simpson), exact "
                                       "(with a per-pixel error bound)")
        ->capture_default_str();
    app.add_option("--placement", placement, "eye, entry, entry-exit or entry-exit-corner (paper A)")
        ->capture_default_str();
    auto* stepOpt = app.add_option("--step", step, "step h in voxels (default 0.5)");
    auto* rateOpt = app.add_option("--rate", rate, "sampling rate in samples per voxel (= 1 / step)")->excludes(stepOpt);
    auto* adaptiveGroup = app.add_option_group("adaptive", "coupled and decoupled (paper B), steps in voxels");
    auto* toleranceOpt = adaptiveGroup->add_option("--tolerance,--eps", adaptive.tolerance,
                                                   "error tolerance eps at the step h0 (exact: per piece)")
                             ->capture_default_str();
    adaptiveGroup->add_option("--h0", adaptive.h0, "initial step")->capture_default_str();
    adaptiveGroup->add_option("--h-min", adaptive.hMin, "smallest step (taken whatever the error)")->capture_default_str();
    adaptiveGroup->add_option("--h-max", hMax, "largest step, or 'none'")->capture_default_str();
    adaptiveGroup->add_option("--accepted-value", accepted, "richardson (D + (D - S)/15) or paper (D + |D - S|/15)")
        ->capture_default_str();
    auto* logRayOpt = adaptiveGroup->add_option("--log-ray", logRay, "record every step try along pixel X,Y's ray");
    adaptiveGroup->add_option("--log", logPath, "CSV of the logged ray's tries (with --log-ray)")->needs(logRayOpt);
    logRayOpt->needs(adaptiveGroup->get_option("--log"));
    auto* precisionOpt = app.add_option("--precision", precision, "double or float (the Vulkan backend: float only, "
                                                                  "its default)")->capture_default_str();
    auto* simdOpt = app.add_option("--simd", simd, "on: float riemann and composite on packets of rays, one per SIMD "
                                                   "lane (bitwise equal to off); off: the scalar path")
                        ->capture_default_str();
    app.add_option("--backend", backend, "cpu (the raycaster of libvri) or vulkan (compute shaders, float)")
        ->capture_default_str();
    app.add_option("--device", device, "Vulkan device: an index of --list-devices or part of a name (default: the first)");
    auto* interpolationOpt =
        app.add_option("--interpolation", interpolation, "Vulkan: shader (grid_sampler.h's trilinear formula in float) "
                                                         "or sampler (the device's 3D texture filtering)")
            ->capture_default_str();
    app.add_flag("--list-devices", listDevicesFlag, "list the Vulkan devices (index, name, type, API version) and exit");
    auto* ertOpt = app.add_option("--early-termination", ert,
                                  "stop rays whose transparency drops below this (0 = off), or 'auto' (once the rest "
                                  "can change no channel by more than 1e-4; 'auto:BOUND' for another bound), the "
                                  "most left out in the stats")
                       ->capture_default_str();
    app.add_flag("--no-skip-empty", noSkip, "march through empty space too (the image does not change)");
    timing.addTo(app);
    app.add_option("-o,--output", output, "output image (.exr: float RGBA)")->required();
    app.add_option("--png", pngPath, "8-bit preview PNG");
    preview.addTo(app);
    app.add_option("--stats", statsPath, "write statistics and provenance as JSON ('-' for stdout)");
    nonfinite.addTo(app);
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
    // Before parsing: listing devices needs none of the options that a render requires.
    for (int i = 1; i < argc; ++i)
        if (std::string_view(argv[i]) == "--list-devices") {
            if (argc != 2) {
                std::cerr << "vri-render: error: --list-devices takes no other argument (see --help)\n";
                return vri::kExitUsage;
            }
            return vri::guardedMain("vri-render", [] { return listDevices(); });
        }
    if (auto exitCode = vri::parseArguments(app, "vri-render", argc, argv)) return *exitCode;

    return vri::guardedMain("vri-render", [&] {
        std::optional<tbb::global_control> threadLimit;
        timing.limitThreads(threadLimit);

        vri::requireExrOutput({"-o", output});
        vri::requireDistinctOutputs({{"-o", output}, {"--png", pngPath}, {"--stats", statsPath}, {"--log", logPath}});
        const bool vulkan = vri::parseBackend(backend, "--backend") == vri::Backend::Vulkan;
        if (vulkan && !*precisionOpt) precision = "float";
        if (!vulkan && !device.empty()) throw vri::Error("--device: needs --backend vulkan");
        if (!vulkan && *interpolationOpt) throw vri::Error("--interpolation: needs --backend vulkan");
        if (vulkan && *simdOpt) throw vri::Error("--simd: needs --backend cpu");
        const vri::VulkanInterpolation interpolationChoice = vri::parseInterpolation(interpolation, "--interpolation");
        // The exact method is vri-reference's: double on the CPU, rays ended by its tolerance.
        const bool exact = method == "exact";
        vri::ExactReferenceOptions exactOptions;
        if (exact) {
            if (vulkan) throw vri::Error("--method exact: runs on --backend cpu only");
            if (*precisionOpt && precision != "double") throw vri::Error("--precision: --method exact is double only");
            if (*stepOpt || *rateOpt) throw vri::Error("--step, --rate: --method exact has no step");
            if (*ertOpt) throw vri::Error("--early-termination: --method exact ends rays by its --tolerance");
            if (!logRay.empty()) throw vri::Error("--log-ray: applies to coupled and decoupled only");
            exactOptions.tolerance = *toleranceOpt ? adaptive.tolerance : 1e-7;
            if (!(exactOptions.tolerance > 0.0))
                throw vri::Error("--tolerance: must be > 0 for --method exact, got " + std::to_string(adaptive.tolerance));
            exactOptions.skipEmptySpace = !noSkip;
            exactOptions.progress = !quiet;
        }
        vri::RenderOptions options;
        if (!exact) options.integrator = vri::parseIntegrator(method, "--method");
        options.placement = vri::parsePlacement(placement, "--placement");
        options.precision = vri::parsePrecision(precision, "--precision");
        options.simd = vri::parseSimd(simd, "--simd");
        if (*stepOpt && !(step > 0.0)) throw vri::Error("--step: must be > 0 voxels, got " + std::to_string(step));
        if (*rateOpt && !(rate > 0.0)) throw vri::Error("--rate: must be > 0 samples per voxel, got " + std::to_string(rate));
        options.samplingRate = *rateOpt ? rate : 1.0 / (*stepOpt ? step : 0.5);
        adaptive.hMax = vri::parseLimit(hMax, "--h-max");
        adaptive.accepted = vri::parseAcceptedValue(accepted, "--accepted-value");
        options.adaptive = adaptive;
        if (!logRay.empty()) options.logPixel = vri::parsePixel(logRay, "--log-ray");
        vri::parseEarlyTermination(ert, "--early-termination", options);
        options.skipEmptySpace = !noSkip;
        options.progress = !quiet;
        // Every option is checked before the render, so that a mistake never leaves some outputs written.
        const vri::PngOptions png = preview.get();

        const vri::SceneSetup setup = sceneOptions.load();
        const vri::Scene& scene = setup.scene;
        const vri::CameraSpec& cam = setup.camera;
        const vri::Camera camera(cam);

        // The Vulkan device is opened once; the volume is uploaded by the first render and reused by repeats.
        std::optional<vri::VulkanRenderer> gpu;
        if (vulkan) {
            vri::VulkanRenderer::validateOptions(options);
            gpu.emplace(device, interpolationChoice);
        }
        struct Frame {
            vri::Image image;
            vri::RenderStats stats;
            std::optional<vri::ExactReferenceStats> exactStats;  // --method exact
            double seconds;
        };
        const auto [frame, wallSeconds] = timing.run([&] {
            if (exact) {
                const vri::ExactReference ref = vri::renderExactReference(scene, camera, exactOptions);
                vri::Image image = ref.image();
                vri::RenderStats s;  // only the non-finite count: the exact method has stats of its own
                s.nonfinite = vri::findNonFinitePixels(image);
                return Frame{std::move(image), s, ref.stats, ref.stats.seconds};
            }
            vri::RenderStats s;
            vri::Image image = gpu ? gpu->render(scene, camera, options, &s) : vri::render(scene, camera, options, &s);
            return Frame{std::move(image), s, std::nullopt, s.seconds};
        });
        const vri::Image& image = frame.image;
        const vri::RenderStats& stats = frame.stats;
        nonfinite.check(stats.nonfinite, "vri-render");

        nlohmann::json record = {{"tool", "vri-render"},
                                 {"command", vri::commandLine(argc, argv)},
                                 {"time_utc", vri::utcTimestamp()},
                                 {"build", vri::buildInfo()},
                                 {"machine", vri::machineInfo()},
                                 {"inputs", setup.inputs},
                                 {"scene", vri::describeScene(scene)},
                                 {"transfer_function", vri::toJson(scene.transferFunction)},
                                 {"camera", vri::toJson(cam)},
                                 {"options", exact ? vri::toJson(exactOptions) : vri::toJson(options)},
                                 {"stats", exact ? vri::toJson(*frame.exactStats) : vri::toJson(stats)}};
        if (exact) record["stats"]["nonfinite_pixels"] = stats.nonfinite.count;
        record["timing"] = timing.toJson(wallSeconds);
        vri::writeExr(output, image, {{"vri:command", record["command"]["shell"].get<std::string>()},
                                      {"vri:options", record["options"].dump()},
                                      {"vri:scene", record["scene"].dump()}});
        if (!pngPath.empty()) vri::writePng(pngPath, image, png);
        if (!statsPath.empty()) vri::writeTextFile(statsPath, record.dump(2) + "\n");
        if (!logPath.empty()) vri::writeTextFile(logPath, vri::adaptiveLogCsv(stats.rayLog));
        if (!quiet && exact)
            std::cerr << "vri-render: exact, " << image.width << "x" << image.height << ", "
                      << frame.exactStats->piecesVisible << " visible pieces in " << timing.summary(wallSeconds)
                      << " on " << frame.exactStats->threads << " threads; error bound max "
                      << record["stats"]["error_bound"]["max"].dump() << "\n";
        else if (!quiet)
            std::cerr << "vri-render: " << image.width << "x" << image.height << ", " << stats.samplesEvaluated
                      << " samples in " << timing.summary(wallSeconds) << " on "
                      << (vulkan ? stats.device : std::to_string(stats.threads) + " threads") << "\n";
        return vri::kExitOk;
    });
}
