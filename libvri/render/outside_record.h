#pragma once
// What vri-outside keeps of an outside renderer's run beside its image: the stats record, in the schema of
// vri's own renders (stats_schema.h) so that vri-diff, vri-tabulate and the charts read it alike, and the
// EXR's metadata.
#include <string>

#include <nlohmann/json.hpp>

#include "libvri/io/image_io.h"
#include "libvri/render/outside_renderer.h"
#include "libvri/render/render_job.h"

namespace vri {

struct OutsideRecord {
    nlohmann::json record;   // provenance, the renderer's own record, backend "outside", rays, quantisation,
                             // non-finite and out-of-range pixels, the renderer's frame times
    ImageMetadata metadata;  // vri:command, vri:options, vri:renderer
};

// Throws vri::Error naming the image's non-finite pixels unless `allowNonFinite`.
OutsideRecord outsideRecord(const OutsideRun& run, const std::string& tool, const nlohmann::json& command,
                            const SceneSetup& setup, const RenderRequest& request, bool allowNonFinite);

}  // namespace vri
