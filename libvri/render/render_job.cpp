#include "libvri/render/render_job.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "libvri/core/out_of_range_pixels.h"
#include "libvri/io/provenance.h"
#include "libvri/render/exact_reference_json.h"
#include "libvri/render/render_json.h"
#include "libvri/render/stats_schema.h"
#include "libvri/util/error.h"
#include "libvri/util/statistics.h"

namespace vri {

namespace {

// Before any device is opened or any frame rendered: the backends that read dense volumes only.
const RenderRequest& checkedAgainstScene(const RenderRequest& request, const Scene& scene) {
    if (scene.sparse && (request.exact || request.backend == Backend::Vulkan))
        throw Error(std::string(request.exact ? "--method exact" : "--backend vulkan") +
                    " renders dense volumes only, and the volume is kept sparse (--storage sparse, or auto for a "
                    ".vdb too large to unpack): use --storage dense");
    if (scene.brick && request.clamp)
        throw Error("--clamp: clamps the joined image, not a brick's layer (vri-merge-tiles --layer)");
    if (scene.brick && (request.exact || request.backend == Backend::Vulkan))
        throw Error(std::string(request.exact ? "--method exact" : "--backend vulkan") +
                    ": not for a brick yet (--bricks renders riemann and composite on the CPU)");
    return request;
}

}  // namespace

RenderJob::RenderJob(RenderRequest request, SceneSetup setup, RenderJobContext context)
    : request_(std::move(request)),
      setup_(std::move(setup)),
      context_(std::move(context)),
      camera_(setup_.camera),
      backend_(checkedAgainstScene(request_, setup_.scene)) {
    if (context_.wantBounds && !request_.exact)
        throw Error("--error-image needs --method exact (no other method has an error bound)");
}

void RenderJob::searchTolerance() {
    if (!request_.maxError) return;
    search_ = searchMaxErrorTolerance(backend_, setup_.scene, camera_, request_);
    request_.exactTolerance = search_->tolerance;
}

RenderFrame RenderJob::frame() {
    if (!request_.exact) return methodFrame(request_.options);
    // The search's accepted render is the first frame at the tolerance it found: not rendered again.
    const ExactReference& ref = search_ && search_->accepted
                                    ? *std::exchange(search_->accepted, nullptr)
                                    : backend_.renderExact(setup_.scene, camera_, request_.exactOptions());
    RenderFrame f;
    f.image = ref.image();
    if (context_.wantBounds) f.bounds = ref.boundImage();
    f.exactStats = ref.stats;
    f.seconds = ref.stats.seconds;
    f.stats.nonfinite = findNonFinitePixels(f.image);
    return f;
}

RenderFrame RenderJob::methodFrame(const RenderOptions& options) {
    RenderFrame f;
    f.image = backend_.render(setup_.scene, camera_, options, &f.stats);
    f.seconds = f.stats.seconds;
    return f;
}

RenderFrame RenderJob::warmUpFrame() {
    if (request_.exact || request_.options.frames == 1) return frame();
    RenderOptions one = request_.options;
    one.frames = 1;
    return methodFrame(one);
}

RenderResult RenderJob::finish(RenderFrame first, nlohmann::json timing) {
    RenderResult result{std::move(first.image),
                        std::move(first.bounds),
                        std::move(first.stats),
                        std::move(first.exactStats),
                        {},
                        {},
                        {}};
    const std::optional<PixelRegion>& region = request_.options.region;
    RenderStats& stats = result.stats;
    if (region && stats.nonfinite.count > 0) {  // in pixels of the whole image, as everything else
        stats.nonfinite.firstX += region->x;
        stats.nonfinite.firstY += region->y;
    }
    if (stats.nonfinite.count > 0) {
        const std::string what = "the image: " + stats.nonfinite.describe() + ": the integration overflowed";
        if (!context_.allowNonFinite)
            throw Error(what + " (a smaller extinction or step, or " + context_.allowNonFiniteName +
                        " to write it anyway)");
        result.warnings.push_back(what);
    }
    if (stats.simpsonRange && stats.simpsonRange->pixelsBeyond > 0)
        result.warnings.push_back(stats.simpsonRange->describe(stats.rays));
    const OutOfRangePixels outOfRange = findOutOfRangePixels(result.image);  // what the method returned
    if (request_.clamp) clampToUnitRange(result.image);

    nlohmann::json record = provenanceRecord(context_.tool, context_.command, setup_, request_);
    record["stats"] = result.exactStats ? toJson(*result.exactStats) : toJson(stats);
    if (result.exactStats) put(record, stats_field::nonfinitePixels, stats.nonfinite.count);
    if (search_) put(record, stats_field::maxErrorSearch, search_->record);
    putOutOfRange(record, outOfRange);
    record["timing"] = std::move(timing);
    if (record.at(stats_field::raysHit.at()) == 0) {
        // A black image with exit 0 looks like a render; said as a warning and kept in the record.
        // A tile (--region) of background is no mistake of the camera's: said so.
        const std::string warning =
            region
                ? "no ray of --region " + region->text() +
                      " enters the volume's box: the region is background, and its image is empty (stats: rays_hit 0)"
                : "no ray enters the volume's box: the camera (eye " + record["camera"]["eye"].dump() + ", target " +
                      record["camera"]["target"].dump() +
                      ") misses the volume, and the image is empty (stats: rays_hit 0)";
        result.warnings.push_back(warning);
        record["warnings"] = {warning};
    }
    const nlohmann::json& command = record["command"];
    result.metadata = {
        {"vri:command", command.contains("shell") ? command["shell"].get<std::string>() : command.dump()},
        {"vri:options", record["options"].dump()},
        {"vri:scene", record["scene"].dump()}};
    if (region) {
        // The images hold the region alone, an ordinary WIDTH x HEIGHT image that every reader takes as it
        // is; where it lies in the camera's image (the record's camera.width x camera.height) is said here.
        record["region"] = toJson(*region);
        result.metadata.emplace_back("vri:region", region->text());
    }
    result.record = std::move(record);
    return result;
}

nlohmann::json provenanceRecord(const std::string& tool, const nlohmann::json& command, const SceneSetup& setup,
                                const RenderRequest& request) {
    nlohmann::json record = {{"tool", tool},
                             {"command", command},
                             {"time_utc", utcTimestamp()},
                             {"build", buildInfo()},
                             {"machine", machineInfo()},
                             {"inputs", setup.inputs},
                             {"scene", describeScene(setup.scene)},
                             {"transfer_function", toJson(setup.scene.transferFunction)},
                             {"camera", toJson(setup.camera)},
                             {"options", toJson(request)}};
    if (!setup.digestRecord.empty()) record["input_digests_from"] = setup.digestRecord.string();
    return record;
}

MedianInterval medianInterval(std::vector<double> values) {
    if (values.empty()) throw Error("a median's interval of no values");
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    // coverage(k) = 1 - 2 P(B < k), B ~ Binomial(n, 1/2): the chance that the median lies between the k-th
    // smallest and the k-th largest.
    const auto coverage = [n](std::size_t k) {
        double below = 0, term = std::pow(0.5, static_cast<double>(n));  // P(B = 0)
        for (std::size_t j = 0; j < k; ++j) {
            below += term;
            term *= static_cast<double>(n - j) / static_cast<double>(j + 1);
        }
        return 1.0 - 2.0 * below;
    };
    std::size_t k = 1;
    while (2 * (k + 1) <= n + 1 && coverage(k + 1) >= 0.95) ++k;
    return {values[k - 1], values[n - k], coverage(k)};
}

std::optional<TimingLoad> timingLoadOf(const nlohmann::json& stats) {
    if (!stats.is_object() || !stats.contains(stats_field::load.at())) return std::nullopt;
    const nlohmann::json& load = stats.at(stats_field::load.at());
    if (!load.is_object()) return std::nullopt;
    return TimingLoad{load.value("other_cores", 0.0), load.value("threads", 1), load.value("cores", 1)};
}

nlohmann::json medianIntervalRecord(const std::vector<double>& values) {
    const MedianInterval ci = medianInterval(values);
    return {{"low", ci.low}, {"high", ci.high}, {"coverage", ci.coverage}};
}

nlohmann::json frameTimingRecord(int warmUpFrames, const std::vector<double>& wallSeconds,
                                 const std::optional<TimingLoad>& load) {
    nlohmann::json record;
    put(record, stats_field::warmUpFrames, warmUpFrames);
    put(record, stats_field::repeats, wallSeconds.size());
    put(record, stats_field::frameSeconds, wallSeconds);
    put(record, stats_field::medianFrameSeconds, median(wallSeconds));
    put(record, stats_field::medianCi, medianIntervalRecord(wallSeconds));
    put(record, stats_field::load, nullptr);
    if (load)
        put(record, stats_field::load,
            {{"other_cores", load->otherCores}, {"threads", load->threads}, {"cores", load->cores},
             {"overloaded", load->overloaded()}});
    return std::move(record["timing"]);
}

}  // namespace vri
