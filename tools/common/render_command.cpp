#include "common/render_command.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <utility>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "common/cli.h"
#include "libvri/core/engine_environment.h"
#include "libvri/io/adaptive_log_csv.h"
#include "libvri/io/image_io.h"
#include "libvri/io/provenance.h"
#include "libvri/render/outside_record.h"
#include "libvri/render/outside_renderer.h"
#include "libvri/render/render_job.h"
#include "libvri/render/render_json.h"
#include "libvri/render/scene_card.h"
#include "libvri/render/stats_schema.h"
#include "libvri/render/tool_flags.h"
#include "libvri/render/verification.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/format.h"
#include "libvri/util/printable.h"

namespace vri {

RenderCommand::RenderCommand(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv, Mode mode)
    : tool_(tool),
      name_(mode == Mode::Outside        ? "vri-outside"
            : mode == Mode::Verify       ? "vri-verify"
            : tool == RenderTool::Render ? "vri-render"
                                         : "vri-reference"),
      argc_(argc),
      argv_(argv),
      app_(std::string(help.description)) {
    app_.footer(std::string(help.footer));
    // Before parsing: listing devices needs none of the options that a render requires.
    mode_ = mode;
    for (int i = 1; tool_ == RenderTool::Render && mode_ == Mode::Vri && i < argc; ++i)
        if (std::string_view(argv[i]) == "--list-devices") {
            if (argc != 2) {
                std::cerr << name_ << ": error: --list-devices takes no other argument (see --help)\n";
                exitCode_ = kExitUsage;
            } else {
                exitCode_ = guardedMain(name_, [&] {
                    const std::vector<BackendDevice> devices = vulkanDevices();
                    if (devices.empty()) throw Error("no Vulkan device found");
                    for (const BackendDevice& d : devices)
                        std::cout << d.index << '\t' << d.name << '\t' << d.type << '\t' << d.apiVersion << '\n';
                    return kExitOk;
                });
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
            if (!group)
                group = app_.add_option_group(std::string(row.group), std::string(renderOptionGroupHelp(row.group)));
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
    if (tool_ == RenderTool::Render && mode_ == Mode::Vri) {
        scene_.addBrickOptions(app_);
        app_.add_flag("--list-devices")
            ->description("list the Vulkan devices (index, name, type, API version) and exit");
        CLI::Option* logRay = byFlag.at("--log-ray");
        CLI::Option* log =
            groups.at("adaptive")
                ->add_option(render_flag::log, logPath_, "CSV of the logged ray's tries (with --log-ray)")
                ->needs(logRay);
        logRay->needs(log);
    }
    timing_.addTo(app_);
    if (mode_ != Mode::Verify)
        app_.add_option("-o,--output", output_, "output image (.exr: float RGBA); required unless --describe");
    if (mode_ == Mode::Verify) {
        app_.add_option("--steps", steps_, "the steps (voxels) of the sweep, at least 3, each one card")
            ->capture_default_str();
        app_.add_option("--min-order", minOrder_, "the observed order of convergence below which the check fails")
            ->capture_default_str()
            ->check(numberAbove(0.0, false));
        app_.add_option("--seeds", seeds_,
                        "with --jitter: run each step's card with this many seeds (--seed, --seed + 1, ...) and test "
                        "the renderer's bias, noise and expectation per pixel against vri's jittered frames "
                        "(16 or more)")
            ->capture_default_str()
            ->check(integerRange(1, 4096));
        app_.add_option("--renderer-jobs", rendererJobs_,
                        "with --seeds: run the renderer on this many seeds' cards at once, each its own process")
            ->capture_default_str()
            ->check(integerRange(1, 64));
        app_.add_option("--reference-tolerance", referenceTolerance_,
                        "the exact reference's quadrature tolerance (its error bound is in the report)")
            ->capture_default_str()
            ->check(numberAbove(0.0, false));
        app_.add_option("--report", reportPath_, "the report as Markdown ('-' for stdout)");
        app_.add_option("--json", jsonPath_, "every number of the report as JSON");
        app_.add_option("--junit", junitPath_, "JUnit XML, one test case per finding, for a CI job's test view");
        app_.add_flag("--exit-zero", exitZero_,
                      "exit 0 when a finding fails too (the report is the result, as in make experiments)");
    }
    if (mode_ != Mode::Vri) {
        app_.add_option(outside_flag::rendererImage, rendererImage_,
                        "what the renderer writes at {output}: exr (RGBA float), png (8 or 16 bit RGBA) or f32 (raw "
                        "little-endian float32 RGBA, row 0 at the top)")
            ->capture_default_str();
        app_.add_flag("--keep-work", keepWork_, "keep the folder with the card, the voxels and the renderer's files");
        app_.add_option(outside_flag::timeout, timeout_,
                        "seconds a run of the renderer may take; past them it is stopped (SIGTERM, SIGKILL 2 s "
                        "later) and this is an error (default: no limit)")
            ->check(numberAbove(0.0, false));
        app_.add_option(outside_flag::rendererName, rendererName_,
                        "what the records and charts call the renderer when its stats name none (default: the "
                        "program's file name)");
        app_.add_option("command", rendererCommand_,
                        "the renderer's command after --, with placeholders {card}, {voxels}, {output}, {stats}, "
                        "{step}, {width}, {height}")
            ->expected(-1);
    }
    CLI::Option* describe =
        app_.add_option("--describe", describePath_,
                        "render nothing: write the scene card, the JSON another renderer needs to reproduce this "
                        "integral (docs/scene-card.md; '-' for stdout)");
    app_.add_option("--describe-voxels", voxelsPath_,
                    "with --describe: also write the volume's voxels as headerless little-endian raw (x fastest), "
                    "which the card names and hashes")
        ->needs(describe);
    app_.add_option(render_flag::png, pngPath_, "8-bit preview PNG");
    preview_.addTo(app_);
    app_.add_option("--error-image", errorImagePath_,
                    "exact: per-pixel error bounds as float RGBA OpenEXR, each bounding the EXR's float32 value (the "
                    "double's bound plus its float32 rounding, rounded up)");
    app_.add_option(render_flag::stats, statsPath_, "write statistics and provenance as JSON ('-' for stdout)");
    app_.add_flag("--allow-nonfinite", allowNonFinite_,
                  "write an image whose pixels overflowed to NaN or infinity (with a warning; the stats count them) "
                  "instead of failing");
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

namespace {

// A folder of its own beside `near`, removed with everything in it unless kept.
class WorkFolder {
public:
    explicit WorkFolder(const std::filesystem::path& near) {
        std::string pattern = (std::filesystem::absolute(near).parent_path() / ".vri-outside-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw Error(pattern + ": cannot create the work folder: " + std::strerror(errno));
        path_ = pattern;
    }
    ~WorkFolder() {
        std::error_code ignored;
        if (!keep_) std::filesystem::remove_all(path_, ignored);
    }
    WorkFolder(const WorkFolder&) = delete;
    WorkFolder& operator=(const WorkFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    void keep() { keep_ = true; }

private:
    std::filesystem::path path_;
    bool keep_ = false;
};

}  // namespace

bool RenderCommand::given(const std::string& option) const {
    const CLI::Option* o = app_.get_option_no_throw(option);
    return o && o->count() > 0;
}

int RenderCommand::describe() {
    const std::vector<OutputArgument> outputs{{"--describe", describePath_}, {"--describe-voxels", voxelsPath_}};
    requireDistinctOutputs(outputs);
    requireOutputsApartFromInputs(outputs, scene_.inputs());
    for (const char* renderOnly : {"-o", render_flag::png, "--error-image", render_flag::stats, render_flag::log})
        if (given(renderOnly))
            throw UsageError(std::string(renderOnly) + ": --describe renders nothing, so it writes no " + renderOnly);
    if (mode_ != Mode::Vri)
        throw UsageError("--describe: " + name_ + " runs a renderer; vri-render --describe writes the card");
    const RenderRequest request = this->request();
    const SceneSetup setup = scene_.load();
    if (!request.exact) validateRender(setup.scene, Camera(setup.camera), request.options);
    // The card names its voxels relative to its own folder (the current one for a card on stdout), so that
    // the two move together.
    std::string voxelsName;
    if (!voxelsPath_.empty()) {
        namespace fs = std::filesystem;
        const fs::path cardFolder =
            describePath_ == "-" ? fs::current_path() : fs::absolute(describePath_).parent_path();
        voxelsName =
            fs::absolute(voxelsPath_).lexically_normal().lexically_relative(cardFolder.lexically_normal()).string();
    }
    auto [card, voxels] = sceneCardWithVoxels(setup, request, voxelsName);
    OutputSet files;
    if (!voxelsPath_.empty()) files.add(voxelsPath_, std::move(voxels));
    files.add(describePath_, card.dump(2) + "\n");
    files.write();
    if (!quiet_ && describePath_ != "-") std::cerr << name_ << ": wrote the scene card " << describePath_ << '\n';
    return kExitOk;
}

void RenderCommand::requireRendererCommand() const {
    if (rendererCommand_.empty())
        throw UsageError("expected the renderer's command after -- (e.g. -- ./my-renderer {card} {output})");
    if (rendererImage_ != "exr" && rendererImage_ != "png" && rendererImage_ != "f32")
        throw UsageError("--renderer-image: expected exr, png or f32, got '" + printable(rendererImage_) + "'");
}

int RenderCommand::runOutside() {
    requireRendererCommand();
    if (output_.empty()) throw UsageError("--output is required");
    requireExrOutput({"-o", output_});
    const std::vector<OutputArgument> outputs{
        {"-o", output_}, {render_flag::png, pngPath_}, {render_flag::stats, statsPath_}};
    requireDistinctOutputs(outputs);
    requireOutputsApartFromInputs(outputs, scene_.inputs());
    for (const char* vriOnly : {"--error-image", render_flag::log})
        if (given(vriOnly)) throw UsageError(std::string(vriOnly) + ": vri's own renders only");
    const RenderRequest request = this->request();
    const PngOptions png = preview_.get();
    const SceneSetup setup = scene_.load();
    const bool volume = setup.scene.volume != nullptr;
    if (!request.exact) validateRender(setup.scene, Camera(setup.camera), request.options);
    auto [card, voxels] = sceneCardWithVoxels(setup, request, volume ? "voxels.raw" : "");

    WorkFolder work(output_);
    if (keepWork_) work.keep();
    OutputSet cardFiles;
    if (volume) cardFiles.add(work.path() / "voxels.raw", std::move(voxels));
    cardFiles.add(work.path() / "card.json", card.dump(2) + "\n");
    cardFiles.write();
    if (!quiet_) std::cerr << name_ << ": running " << shellQuote(rendererCommand_[0]) << " on the card\n";
    OutsideRun run = runOutsideRenderer({rendererCommand_, rendererImage_, rendererName_, timeout_}, card, work.path());
    if (keepWork_) std::cerr << name_ << ": kept the work folder " << work.path().string() << '\n';

    const auto [record, metadata] =
        outsideRecord(run, name_, commandLine(argc_, argv_), setup, request, allowNonFinite_);
    OutputSet files;
    files.add(output_, encodeExr(output_, run.image, metadata));
    if (!pngPath_.empty()) files.add(pngPath_, encodePng(pngPath_, run.image, png));
    if (!statsPath_.empty()) files.add(statsPath_, record.dump(2) + "\n");
    files.write();
    if (!quiet_)
        std::cerr << name_ << ": " << run.renderer.value("name", rendererCommand_[0]) << ", " << run.image.width << "x"
                  << run.image.height << " (" << run.quantisation << "), " << record.at(stats_field::medianFrameSeconds.at())
                  << " s (" << run.timed << ")\n";
    return kExitOk;
}

int RenderCommand::runVerify() {
    requireRendererCommand();
    const std::vector<OutputArgument> outputs{
        {"--report", reportPath_}, {"--json", jsonPath_}, {"--junit", junitPath_}};
    requireDistinctOutputs(outputs);
    requireOutputsApartFromInputs(outputs, scene_.inputs());
    for (const char* vriOnly : {"--error-image", render_flag::log, render_flag::png, render_flag::stats})
        if (given(vriOnly)) throw UsageError(std::string(vriOnly) + ": vri-verify writes --report, --json, --junit");
    VerificationOptions options;
    options.steps = parsePositiveList(steps_, "--steps");
    options.minOrder = minOrder_;
    options.referenceTolerance = referenceTolerance_;
    const RenderRequest request = this->request();
    if (request.exact || isSimpson(request.options.integrator))
        throw UsageError("--method: vri-verify sweeps the step of a fixed-step method (riemann, composite)");
    if (request.wasGiven("--placement")) options.placement = request.options.placement;
    options.seeds = seeds_;
    options.rendererJobs = rendererJobs_;
    if (rendererJobs_ > 1 && seeds_ < 2)
        throw UsageError("--renderer-jobs: runs the cards of several seeds at once; give --seeds N (and --jitter)");
    if (seeds_ > 1 && !request.options.jitter)
        throw UsageError("--seeds: tests a jittered renderer; give --jitter (and --seed for the first seed)");
    if (request.options.jitter && seeds_ < 2)
        throw UsageError("--jitter: a jittered renderer is verified over seeds: give --seeds N (16 or more)");
    if (request.options.frames > 1)
        throw UsageError("--frames: vri-verify runs each card once per seed (--seeds), one frame each");
    const SceneSetup setup = scene_.load();
    WorkFolder work(reportPath_.empty() || reportPath_ == "-" ? std::filesystem::path("report")
                                                              : std::filesystem::path(reportPath_));
    if (keepWork_) work.keep();
    const VerificationReport report = verifyRenderer({rendererCommand_, rendererImage_, rendererName_, timeout_}, setup, request,
                                                     options, work.path(), [&](const std::string& line) {
                                                         if (!quiet_) std::cerr << name_ << ": " << line << '\n';
                                                     });
    if (keepWork_) std::cerr << name_ << ": kept the work folder " << work.path().string() << '\n';
    OutputSet files;
    if (!reportPath_.empty()) files.add(reportPath_, report.markdown);
    if (!jsonPath_.empty()) {
        nlohmann::json record = report.record;
        record["command"] = commandLine(argc_, argv_);
        record["build"] = buildInfo();
        record["inputs"] = setup.inputs;
        if (!setup.digestRecord.empty()) record["input_digests_from"] = setup.digestRecord.string();
        files.add(jsonPath_, record.dump(2) + "\n");
    }
    if (!junitPath_.empty()) files.add(junitPath_, report.junit);
    files.write();
    for (const nlohmann::json& f : report.record["findings"])
        std::cerr << name_ << ": " << (f["passed"].get<bool>() ? "pass" : "FAIL") << ": "
                  << f["name"].get<std::string>() << ": " << f["message"].get<std::string>() << '\n';
    return report.passed || exitZero_ ? kExitOk : kExitVerifyFailed;
}

int RenderCommand::run() {
    if (exitCode_) return *exitCode_;
    return guardedMain(name_, [&] {
        std::optional<tbb::global_control> threadLimit;  // set once every option is checked
        requireUtf8Arguments(argc_, argv_);
        if (!describePath_.empty()) return describe();
        if (mode_ == Mode::Outside) return runOutside();
        if (mode_ == Mode::Verify) return runVerify();
        if (output_.empty()) throw UsageError("--output is required (or --describe, which renders nothing)");
        requireExrOutput({"-o", output_});
        if (!errorImagePath_.empty()) requireExrOutput({"--error-image", errorImagePath_});
        const std::vector<OutputArgument> outputs{{"-o", output_},
                                                  {render_flag::png, pngPath_},
                                                  {"--error-image", errorImagePath_},
                                                  {render_flag::stats, statsPath_},
                                                  {render_flag::log, logPath_}};
        requireDistinctOutputs(outputs);
        requireOutputsApartFromInputs(outputs, scene_.inputs());
        // Every option is checked before the render, so that a mistake never leaves some outputs written.
        RenderRequest request = this->request();
        checkEngineEnvironment();  // after the usage errors (exit 64), whether or not this render reads it
        timing_.setFrames(request.warmUp, request.repeat, name_, quiet_);
        const PngOptions png = preview_.get();
        const std::optional<PixelRegion> region = request.options.region;
        if (region) {  // before the volume is read: the two options disagree, whatever the scene
            const glm::ivec2 size = scene_.imageSize();
            if (!region->inside(size.x, size.y))
                throw UsageError("--region: " + region->text() + " reaches outside the " + std::to_string(size.x) +
                                 "x" + std::to_string(size.y) + " image of --size (expected X + WIDTH <= " +
                                 std::to_string(size.x) + " and Y + HEIGHT <= " + std::to_string(size.y) + ")");
        }

        timing_.limitThreads(threadLimit, name_);
        RenderJob job(std::move(request), scene_.load(),
                      {name_, commandLine(argc_, argv_), !errorImagePath_.empty(), allowNonFinite_});
        job.searchTolerance();
        auto [frame, wallSeconds] = timing_.run([&] { return job.frame(); }, [&] { return job.warmUpFrame(); });
        const RenderResult result = job.finish(std::move(frame), timing_.toJson(wallSeconds));
        for (const std::string& warning : result.warnings) std::cerr << name_ << ": warning: " << warning << '\n';
        const Image& image = result.image;
        const nlohmann::json& record = result.record;
        const RenderStats& stats = result.stats;
        const ImageMetadata& metadata = result.metadata;
        OutputSet files;
        files.add(output_, encodeExr(output_, image, metadata));
        if (!pngPath_.empty()) files.add(pngPath_, encodePng(pngPath_, image, png));
        if (result.bounds) files.add(errorImagePath_, encodeExr(errorImagePath_, *result.bounds, metadata));
        if (!statsPath_.empty()) files.add(statsPath_, record.dump(2) + "\n");
        if (!logPath_.empty()) files.add(logPath_, adaptiveLogCsv(stats.rayLog));
        files.write();
        if (!quiet_) {
            std::cerr << name_ << ": " << record["options"]["method"].get<std::string>() << ", " << image.width << "x"
                      << image.height
                      << (region ? " at " + std::to_string(region->x) + "," + std::to_string(region->y) : "") << ", ";
            if (result.exactStats)
                std::cerr << result.exactStats->piecesVisible << " visible pieces in " << timing_.summary(wallSeconds)
                          << " on " << result.exactStats->threads << " threads; error bound max "
                          << record.at(stats_field::errorBoundMax.at()).dump() << "\n";
            else
                std::cerr << stats.samplesEvaluated << " samples in " << timing_.summary(wallSeconds) << " on "
                          << (stats.device.empty() ? std::to_string(stats.threads) + " threads" : stats.device) << "\n";
        }
        return kExitOk;
    });
}

int renderMain(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv) {
    return RenderCommand::fromArgs(tool, help, argc, argv).run();
}

int outsideMain(const RenderCommandHelp& help, int argc, char** argv) {
    return RenderCommand::outsideFromArgs(help, argc, argv).run();
}

int verifyMain(const RenderCommandHelp& help, int argc, char** argv) {
    return RenderCommand::verifyFromArgs(help, argc, argv).run();
}

}  // namespace vri
