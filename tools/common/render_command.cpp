#include "common/render_command.h"

#include <iostream>
#include <map>
#include <utility>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "common/cli.h"
#include "common/exact_reference_json.h"
#include "common/max_error_search.h"
#include "common/render_backend.h"
#include "common/render_json.h"
#include "libvri/core/engine_environment.h"
#include "libvri/core/exact_reference.h"
#include "libvri/io/adaptive_log_csv.h"
#include "libvri/io/image_io.h"
#include "libvri/io/provenance.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

// One computation of the image: what it gave and what the stats file says about it.
struct Frame {
    Image image;
    std::optional<Image> bounds;  // the exact method's per-pixel error bounds, when --error-image asks for them
    RenderStats stats;            // the exact method: only the non-finite count (it has stats of its own)
    std::optional<ExactReferenceStats> exactStats;
    double seconds;
};

}  // namespace

RenderCommand::RenderCommand(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv)
    : tool_(tool),
      name_(tool == RenderTool::Render ? "vri-render" : "vri-reference"),
      argc_(argc),
      argv_(argv),
      app_(std::string(help.description)) {
    app_.footer(std::string(help.footer));
    // Before parsing: listing devices needs none of the options that a render requires.
    for (int i = 1; tool_ == RenderTool::Render && i < argc; ++i)
        if (std::string_view(argv[i]) == "--list-devices") {
            if (argc != 2) {
                std::cerr << name_ << ": error: --list-devices takes no other argument (see --help)\n";
                exitCode_ = kExitUsage;
            } else {
                exitCode_ = guardedMain(name_, [&] { return listVulkanDevices(name_); });
            }
            return;
        }

    scene_.addTo(app_);
    const RenderRequest defaults(tool_);
    std::map<std::string_view, CLI::Option_group*> groups;
    std::map<std::string_view, CLI::Option*> byFlag;
    slots_.reserve(renderOptionTable().size());  // CLI11 keeps pointers into them
    for (const RenderOptionRow& row : renderOptionTable()) {
        if (!row.takenBy(tool_)) continue;
        CLI::App* target = &app_;
        if (!row.group.empty()) {
            auto& group = groups[row.group];
            if (!group) group = app_.add_option_group(std::string(row.group), std::string(renderOptionGroupHelp(row.group)));
            target = group;
        }
        const std::string names(row.names), help(row.help);
        CLI::Option* option = nullptr;
        switch (row.kind) {
        case OptionValueKind::Number:
            option = target->add_option(names, std::get<double>(slots_.emplace_back(0.0)), help);
            break;
        case OptionValueKind::Count:
            option = target->add_option(names, std::get<int>(slots_.emplace_back(0)), help);
            break;
        case OptionValueKind::Text:
            option = target->add_option(names, std::get<std::string>(slots_.emplace_back(std::string())), help);
            break;
        case OptionValueKind::Flag:
            option = target->add_flag(names, std::get<bool>(slots_.emplace_back(false)), help);
            break;
        }
        if (const std::string shown = row.shownDefault(defaults); !shown.empty()) option->default_str(shown);
        tableOptions_.push_back({&row, option});
        byFlag[row.flag()] = option;
    }
    for (const TableOption& t : tableOptions_)
        if (!t.row->excludes.empty()) t.option->excludes(byFlag.at(t.row->excludes));
    if (tool_ == RenderTool::Render) {
        app_.add_flag("--list-devices")->description("list the Vulkan devices (index, name, type, API version) and exit");
        CLI::Option* logRay = byFlag.at("--log-ray");
        CLI::Option* log = groups.at("adaptive")
                               ->add_option("--log", logPath_, "CSV of the logged ray's tries (with --log-ray)")
                               ->needs(logRay);
        logRay->needs(log);
    }
    timing_.addTo(app_);
    app_.add_option("-o,--output", output_, "output image (.exr: float RGBA)")->required();
    app_.add_option("--png", pngPath_, "8-bit preview PNG");
    preview_.addTo(app_);
    app_.add_option("--error-image", errorImagePath_,
                    "exact: per-pixel error bounds as float RGBA OpenEXR, each bounding the EXR's float32 value (the "
                    "double's bound plus its float32 rounding, rounded up)");
    app_.add_option("--stats", statsPath_, "write statistics and provenance as JSON ('-' for stdout)");
    nonfinite_.addTo(app_);
    app_.add_flag("-q,--quiet", quiet_, "no progress on stderr");
    exitCode_ = parseArguments(app_, name_, argc, argv);
}

RenderRequest RenderCommand::request() const {
    RenderRequest request(tool_);
    for (const TableOption& t : tableOptions_) {
        if (t.option->count() == 0) continue;
        const std::string text = t.row->kind == OptionValueKind::Flag ? "true" : t.option->as<std::string>();
        t.row->apply(text, std::string(t.row->flag()), request);
        request.given.push_back(t.row->flag());
    }
    request.options.progress = !quiet_;
    finishRenderRequest(request);
    return request;
}

int RenderCommand::run() {
    if (exitCode_) return *exitCode_;
    return guardedMain(name_, [&] {
        std::optional<tbb::global_control> threadLimit;  // set once every option is checked
        requireUtf8Arguments(argc_, argv_);
        requireExrOutput({"-o", output_});
        if (!errorImagePath_.empty()) requireExrOutput({"--error-image", errorImagePath_});
        const std::vector<OutputArgument> outputs{{"-o", output_},
                                                  {"--png", pngPath_},
                                                  {"--error-image", errorImagePath_},
                                                  {"--stats", statsPath_},
                                                  {"--log", logPath_}};
        requireDistinctOutputs(outputs);
        requireOutputsApartFromInputs(outputs, scene_.inputs());
        // Every option is checked before the render, so that a mistake never leaves some outputs written.
        RenderRequest request = this->request();
        checkEngineEnvironment();  // after the usage errors (exit 64), whether or not this render reads it
        if (!errorImagePath_.empty() && !request.exact)
            throw Error("--error-image needs --method exact (no other method has an error bound)");
        timing_.setFrames(request.warmUp, request.repeat, name_, quiet_);
        const PngOptions png = preview_.get();
        const std::optional<PixelRegion>& region = request.options.region;
        if (region) {  // before the volume is read: the two options disagree, whatever the scene
            const glm::ivec2 size = scene_.imageSize();
            if (!region->inside(size.x, size.y))
                throw UsageError("--region: " + region->text() + " reaches outside the " + std::to_string(size.x) +
                                 "x" + std::to_string(size.y) + " image of --size (expected X + WIDTH <= " +
                                 std::to_string(size.x) + " and Y + HEIGHT <= " + std::to_string(size.y) + ")");
        }

        timing_.limitThreads(threadLimit, name_);
        const SceneSetup setup = scene_.load();
        const Scene& scene = setup.scene;
        if (scene.sparse && (request.exact || request.backend == Backend::Vulkan))
            throw Error(std::string(request.exact ? "--method exact" : "--backend vulkan") +
                        " renders dense volumes only, and the volume is kept sparse (--storage sparse, or auto for a "
                        ".vdb too large to unpack): use --storage dense");
        const Camera camera(setup.camera);
        RenderBackend backend(request);
        std::optional<MaxErrorSearch> search;
        if (request.maxError) {
            search = searchMaxErrorTolerance(backend, scene, camera, request);
            request.exactTolerance = search->tolerance;
        }
        auto [frame, wallSeconds] = timing_.run([&] {
            if (request.exact) {
                // The search's accepted render is the first frame at the tolerance it found (a warm-up, or
                // the first timed frame): not rendered again.
                const ExactReference& ref = search && search->accepted
                                                ? *std::exchange(search->accepted, nullptr)
                                                : backend.renderExact(scene, camera, request.exactOptions());
                Frame f{ref.image(), std::nullopt, {}, ref.stats, ref.stats.seconds};
                if (!errorImagePath_.empty()) f.bounds = ref.boundImage();
                f.stats.nonfinite = findNonFinitePixels(f.image);
                return f;
            }
            Frame f{{}, std::nullopt, {}, std::nullopt, 0.0};
            f.image = backend.render(scene, camera, request.options, &f.stats);
            f.seconds = f.stats.seconds;
            return f;
        });
        if (region && frame.stats.nonfinite.count > 0) {  // in pixels of the whole image, as everything else
            frame.stats.nonfinite.firstX += region->x;
            frame.stats.nonfinite.firstY += region->y;
        }
        const RenderStats& stats = frame.stats;
        nonfinite_.check(stats.nonfinite, name_);
        if (stats.simpsonRange && stats.simpsonRange->pixelsBeyond > 0)
            std::cerr << name_ << ": warning: " << stats.simpsonRange->describe(stats.rays) << '\n';
        const OutOfRangePixels outOfRange = findOutOfRangePixels(frame.image);  // what the method returned
        if (request.clamp) clampToUnitRange(frame.image);
        const Image& image = frame.image;

        // The provenance record: what was run, on what, with which settings, and what it measured.
        nlohmann::json record = {{"tool", name_},
                                 {"command", commandLine(argc_, argv_)},
                                 {"time_utc", utcTimestamp()},
                                 {"build", buildInfo()},
                                 {"machine", machineInfo()},
                                 {"inputs", setup.inputs},
                                 {"scene", describeScene(scene)},
                                 {"transfer_function", toJson(scene.transferFunction)},
                                 {"camera", toJson(setup.camera)},
                                 {"options", toJson(request)},
                                 {"stats", frame.exactStats ? toJson(*frame.exactStats) : toJson(stats)}};
        if (frame.exactStats) record["stats"]["nonfinite_pixels"] = stats.nonfinite.count;
        if (search) record["stats"]["max_error_search"] = search->record;
        record["stats"]["out_of_range_pixels"] = toJson(outOfRange);
        record["timing"] = timing_.toJson(wallSeconds);
        if (record["stats"]["rays_hit"] == 0) {
            // A black image with exit 0 looks like a render; said on stderr and kept in the stats.
            // A tile (--region) of background is no mistake of the camera's: said so.
            const std::string warning =
                region ? "no ray of --region " + region->text() +
                             " enters the volume's box: the region is background, and its image is empty (stats: rays_hit 0)"
                       : "no ray enters the volume's box: the camera (eye " + record["camera"]["eye"].dump() +
                             ", target " + record["camera"]["target"].dump() +
                             ") misses the volume, and the image is empty (stats: rays_hit 0)";
            std::cerr << name_ << ": warning: " << warning << '\n';
            record["warnings"] = {warning};
        }
        ImageMetadata metadata = {{"vri:command", record["command"]["shell"].get<std::string>()},
                                  {"vri:options", record["options"].dump()},
                                  {"vri:scene", record["scene"].dump()}};
        if (region) {
            // The images hold the region alone, an ordinary WIDTH x HEIGHT image that every reader takes as it
            // is; where it lies in the camera's image (the stats' camera.width x camera.height) is said here.
            record["region"] = toJson(*region);
            metadata.emplace_back("vri:region", region->text());
        }
        OutputSet files;
        files.add(output_, encodeExr(output_, image, metadata));
        if (!pngPath_.empty()) files.add(pngPath_, encodePng(pngPath_, image, png));
        if (frame.bounds) files.add(errorImagePath_, encodeExr(errorImagePath_, *frame.bounds, metadata));
        if (!statsPath_.empty()) files.add(statsPath_, record.dump(2) + "\n");
        if (!logPath_.empty()) files.add(logPath_, adaptiveLogCsv(stats.rayLog));
        files.write();
        if (!quiet_) {
            std::cerr << name_ << ": " << record["options"]["method"].get<std::string>() << ", " << image.width << "x"
                      << image.height << (region ? " at " + std::to_string(region->x) + "," + std::to_string(region->y) : "")
                      << ", ";
            if (frame.exactStats)
                std::cerr << frame.exactStats->piecesVisible << " visible pieces in " << timing_.summary(wallSeconds)
                          << " on " << frame.exactStats->threads << " threads; error bound max "
                          << record["stats"]["error_bound"]["max"].dump() << "\n";
            else
                std::cerr << stats.samplesEvaluated << " samples in " << timing_.summary(wallSeconds) << " on "
                          << (stats.device.empty() ? std::to_string(stats.threads) + " threads" : stats.device) << "\n";
        }
        return kExitOk;
    });
}

}  // namespace vri
