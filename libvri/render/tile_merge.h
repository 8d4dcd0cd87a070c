#pragma once
// vri-merge-tiles' work: the tiles of one render (vri-render or vri-reference run with --region, each an
// EXR of its region and a stats JSON) checked to make up one image and joined into the image the untiled
// render writes, bit for bit (every pixel of a region render is the whole render's pixel), and one stats
// record whose fields are combined by the rules of the stats schema (stats_schema.h).
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/core/image.h"
#include "libvri/io/image_io.h"
#include "libvri/render/stats_schema.h"

namespace vri {

// Every field the schema declares (stats_schema.h) is combined by its rule; a rule for an object covers its
// members. A field the schema lacks, a Same field the tiles disagree in, or one only some tiles have is not
// combined: it becomes null and is listed in the merged record's "not_combined", so that no tile's value is
// read as the image's.
// The combined "stats" and "timing" records of tiles (each a whole stats file) and the dotted names of
// the fields that were not combined: {"stats": ..., "timing": ..., "not_combined": [...]}. `names`
// name the tiles' files for errors. Throws vri::Error when the tiles disagree in an Agree field or in
// the length of an array.
nlohmann::json combineTileStats(const std::vector<nlohmann::json>& records, const std::vector<std::string>& names);

// One tile as given: its image and its stats file.
struct TileFiles {
    std::string image, stats;
};

struct MergedTiles {
    Image image;             // the whole image
    nlohmann::json record;   // the stats record, less the merge's own command and time
    ImageMetadata metadata;  // the EXR attributes of the untiled render, but vri:command
};

// Reads the tiles and checks that they belong to one render (the same tool, build, inputs, scene,
// transfer function, camera and options), that each image is its stats' region, and that the regions
// cover the camera's image exactly once; throws vri::Error naming the file and what was expected.
MergedTiles mergeTiles(const std::vector<TileFiles>& tiles);

}  // namespace vri
