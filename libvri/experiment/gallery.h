#pragma once
// The results gallery, read from every <results>/*/manifest.json: results/README.md opens with an index
// (paper item -> section -> how ours agrees, sections in the papers' order: paper A, paper B, own studies),
// then each experiment's section: what the paper says, its images as scene-by-run grids, its tables,
// figures and agreement, and the commit and manifest it came from. A long section gets a page of its own,
// results/<experiment>.md, which the index links to. Image and table links are relative to the results
// folder. Each agreement's {{table:...}} and {{json:...}} numbers are filled from its experiment's files
// (caption_numbers.h); one that does not resolve is a vri::Error.
#include <filesystem>
#include <string>
#include <vector>

namespace vri {

struct GalleryPage {
    std::string name;  // in the results folder: "README.md", "<experiment>.md"
    std::string text;
};

std::vector<GalleryPage> galleryPages(const std::filesystem::path& resultsRoot);

}  // namespace vri
