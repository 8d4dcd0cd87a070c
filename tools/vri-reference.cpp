// vri-reference: the reference image of a scene, solved accurately with a bound on its error, or as
// paper B computed its reference (a Riemann sum with a 0.01-voxel step).
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
#include "vri/io/image_io.h"
#include "vri/io/provenance.h"
#include "vri/util/atomic_file.h"

namespace {

// One computation of the image: what it gave and what the stats file says about it.
struct Result {
    vri::Image image;
    std::optional<vri::Image> bounds;  // the exact method's per-pixel error bounds
    vri::NonFinitePixels nonfinite;
    nlohmann::json stats;
    double seconds;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Reference image of a volume (or an analytic field): the volume rendering integral along each "
                 "pixel's ray solved to near double precision with a bound on its error (--method exact), or "
                 "paper B's reference, a Riemann sum with a small step (--method riemann). Float RGBA OpenEXR, "
                 "an optional PNG preview, error-bound image and JSON stats."};
    app.footer(R"(Examples:
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                -o bonsai-exact.exr --error-image bonsai-bound.exr --stats bonsai-exact.json
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                --method riemann --step 0.01 -o bonsai-riemann.exr
  vri-diff bonsai-riemann.exr bonsai-exact.exr --threshold 0.001

exact: the ray is split where the trilinear field changes form (voxel-index planes) and where it crosses a
transfer-function point; on each piece the scalar, extinction and colour are cubics, the optical depth an
exact quartic, and the outer integral adaptive Gauss-Kronrod. The stats give the error bound per channel.
riemann: vri-render's Riemann sum, entry placement, double precision, --step in voxels.)");

    vri::SceneOptions sceneOptions;
    std::string method = "exact", output, pngPath, errorPath, statsPath;
    double step = 0.01, tolerance = vri::ExactReferenceOptions{}.tolerance;
    vri::FrameTiming timing;
    bool quiet = false;
    vri::PreviewOptions preview;
    vri::NonFiniteOption nonfinite;
    sceneOptions.addTo(app);
    app.add_option("--method", method, "exact (piecewise cubic, with an error bound) or riemann (paper B's reference)")
        ->capture_default_str();
    auto* stepOpt = app.add_option("--step", step, "riemann: step h in voxels")->capture_default_str();
    auto* toleranceOpt =
        app.add_option("--tolerance", tolerance, "exact: quadrature error allowed per transfer-function piece of a ray")
            ->capture_default_str();
    timing.addTo(app);
    app.add_option("-o,--output", output, "output image (.exr: float RGBA)")->required();
    app.add_option("--png", pngPath, "8-bit preview PNG");
    preview.addTo(app);
    app.add_option("--error-image", errorPath, "exact: per-pixel error bounds as float RGBA OpenEXR");
    app.add_option("--stats", statsPath, "write statistics and provenance as JSON ('-' for stdout)");
    nonfinite.addTo(app);
    app.add_flag("-q,--quiet", quiet, "no progress on stderr");
    if (auto exitCode = vri::parseArguments(app, "vri-reference", argc, argv)) return *exitCode;

    return vri::guardedMain("vri-reference", [&] {
        std::optional<tbb::global_control> threadLimit;
        timing.limitThreads(threadLimit);
        vri::requireExrOutput({"-o", output});
        if (!errorPath.empty()) vri::requireExrOutput({"--error-image", errorPath});
        vri::requireDistinctOutputs(
            {{"-o", output}, {"--png", pngPath}, {"--error-image", errorPath}, {"--stats", statsPath}});
        if (method != "exact" && method != "riemann")
            throw vri::Error("--method: unknown method '" + method + "' (expected exact or riemann)");
        const bool exact = method == "exact";
        if (exact && *stepOpt) throw vri::Error("--step applies to --method riemann only");
        if (!exact && *toleranceOpt) throw vri::Error("--tolerance applies to --method exact only");
        if (!exact && !errorPath.empty())
            throw vri::Error("--error-image needs --method exact (a Riemann sum has no error bound)");
        if (!(step > 0.0)) throw vri::Error("--step: must be > 0 voxels, got " + std::to_string(step));
        if (!(tolerance > 0.0)) throw vri::Error("--tolerance: must be > 0, got " + std::to_string(tolerance));

        const vri::PngOptions png = preview.get();
        vri::ExactReferenceOptions exactOptions;
        exactOptions.tolerance = tolerance;
        exactOptions.progress = !quiet;
        vri::RenderOptions riemannOptions;  // paper B's reference: Riemann, entry placement, double
        riemannOptions.integrator = vri::Integrator::Riemann;
        riemannOptions.placement = vri::Placement::EntryAlign;
        riemannOptions.precision = vri::Precision::Double;
        riemannOptions.samplingRate = 1.0 / step;
        riemannOptions.progress = !quiet;

        const vri::SceneSetup setup = sceneOptions.load();
        const vri::Camera camera(setup.camera);
        auto compute = [&]() -> Result {
            if (exact) {
                const vri::ExactReference ref = vri::renderExactReference(setup.scene, camera, exactOptions);
                vri::Image image = ref.image();
                const vri::NonFinitePixels found = vri::findNonFinitePixels(image);
                nlohmann::json stats = vri::toJson(ref.stats);
                stats["nonfinite_pixels"] = found.count;
                return {std::move(image), ref.boundImage(), found, std::move(stats), ref.stats.seconds};
            }
            vri::RenderStats stats;
            vri::Image image = vri::render(setup.scene, camera, riemannOptions, &stats);
            return {std::move(image), std::nullopt, stats.nonfinite, vri::toJson(stats), stats.seconds};
        };
        const auto [result, wallSeconds] = timing.run(compute);
        nonfinite.check(result.nonfinite, "vri-reference");

        nlohmann::json record = {{"tool", "vri-reference"},
                                 {"command", vri::commandLine(argc, argv)},
                                 {"time_utc", vri::utcTimestamp()},
                                 {"build", vri::buildInfo()},
                                 {"machine", vri::machineInfo()},
                                 {"inputs", setup.inputs},
                                 {"scene", vri::describeScene(setup.scene)},
                                 {"transfer_function", vri::toJson(setup.scene.transferFunction)},
                                 {"camera", vri::toJson(setup.camera)},
                                 {"options", exact ? vri::toJson(exactOptions) : vri::toJson(riemannOptions)},
                                 {"stats", result.stats}};
        record["timing"] = timing.toJson(wallSeconds);
        const vri::ImageMetadata metadata = {{"vri:command", record["command"]["shell"].get<std::string>()},
                                             {"vri:options", record["options"].dump()},
                                             {"vri:scene", record["scene"].dump()}};
        vri::writeExr(output, result.image, metadata);
        if (!pngPath.empty()) vri::writePng(pngPath, result.image, png);
        if (!errorPath.empty()) vri::writeExr(errorPath, *result.bounds, metadata);
        if (!statsPath.empty()) vri::writeTextFile(statsPath, record.dump(2) + "\n");
        if (!quiet) {
            std::cerr << "vri-reference: " << method << ", " << result.image.width << "x" << result.image.height
                      << " in " << timing.summary(wallSeconds) << " on "
                      << result.stats["threads"].get<int>() << " threads";
            if (exact) std::cerr << "; error bound max " << result.stats["error_bound"]["max"].dump();
            std::cerr << "\n";
        }
        return vri::kExitOk;
    });
}
