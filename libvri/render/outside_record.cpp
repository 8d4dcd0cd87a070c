#include "libvri/render/outside_record.h"

#include <cstdint>
#include <utility>

#include "libvri/core/nonfinite_pixels.h"
#include "libvri/core/out_of_range_pixels.h"
#include "libvri/render/render_json.h"
#include "libvri/render/stats_schema.h"
#include "libvri/util/error.h"

namespace vri {

OutsideRecord outsideRecord(const OutsideRun& run, const std::string& tool, const nlohmann::json& command,
                            const SceneSetup& setup, const RenderRequest& request, bool allowNonFinite) {
    const NonFinitePixels nonfinite = findNonFinitePixels(run.image);
    if (nonfinite.count > 0 && !allowNonFinite)
        throw Error("the renderer's image: " + nonfinite.describe() + " (--allow-nonfinite to keep it)");
    nlohmann::json record = provenanceRecord(tool, command, setup, request);
    record["inputs"].push_back(run.renderer["executable"]);
    record["renderer"] = run.renderer;
    put(record, stats_field::backend, "outside");
    put(record, stats_field::rays, static_cast<std::uint64_t>(run.image.width) * run.image.height);
    put(record, stats_field::quantisation, run.quantisation);
    put(record, stats_field::nonfinitePixels, nonfinite.count);
    putOutOfRange(record, findOutOfRangePixels(run.image));
    record["timing"] = frameTimingRecord(0, run.wallSeconds);
    put(record, stats_field::timed, run.timed);
    // The renderer's command as given, placeholders and all: the work folder is a fresh name each run, and the
    // image's bytes must not depend on it (the stats keep the words as run).
    ImageMetadata metadata = {{"vri:command", record["command"]["shell"].get<std::string>()},
                              {"vri:options", record["options"].dump()},
                              {"vri:renderer", run.renderer["command"].dump()}};
    return {std::move(record), std::move(metadata)};
}

}  // namespace vri
