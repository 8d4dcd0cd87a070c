#pragma once
// The gallery's images as a matrix a reader can scan: one row per scene (dataset), one column per
// method run, a Markdown table of thumbnails with both labelled, cut into tables of a few columns so
// that no thumbnail shrinks to nothing (never one row of fifty).
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace vri {

struct GridImage {
    std::string id;      // the step's id: the image's alt text, so a reader can find its files
    std::string file;    // its path, as the link should give it
    std::string row;     // the scene it shows ("" for an image that belongs to none, a command's)
    std::string column;  // the run (or comparison) it shows, without the scene
};

// Where each of a manifest's gallery images (`list`: outputs.images or outputs.diff_images) goes in its
// experiment's scene-by-run matrix: a render's row is its scene and its column its run; a difference image's row is its run's scene and its column "RUN vs REFERENCE",
// or its comparison's id when another comparison of the same pair took that column already (two
// comparisons of one run, say on different scales). A command's image has no scene.
// `steps` are the manifest's, `dir` the folder the files' paths begin with.
std::vector<GridImage> gridImages(const nlohmann::json& list, const nlohmann::json& steps, const std::string& dir);

// At most this many image columns per table.
inline constexpr std::size_t kGridColumns = 6;

// Markdown tables: rows and columns in order of first appearance, a cell left empty where a scene has
// no such run; `corner` heads the row labels. "" when there are no images.
std::string imageGrid(const std::vector<GridImage>& images, const std::string& corner);

}  // namespace vri
