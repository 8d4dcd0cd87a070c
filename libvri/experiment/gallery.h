#pragma once
// The results gallery, read from every <results>/*/manifest.json: results/README.md opens with an index
// (paper item -> section -> how ours agrees, sections in the papers' order: paper A, paper B, own studies,
// then the pages scripts wrote),
// then each experiment's section: what the paper says, its images as scene-by-run grids, its tables,
// figures and agreement, and the commit and manifest it came from. A long section gets a page of its own,
// results/<experiment>.md, which the index links to. Image and table links are relative to the results
// folder. Each agreement's {{table:...}} and {{json:...}} numbers are filled from its experiment's files
// (caption_numbers.h); one that does not resolve is a vri::Error.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace vri {

struct GalleryPage {
    std::string name;  // in the results folder: "README.md", "<experiment>.md"
    std::string text;
};

// What the index knows of an experiment: its manifest, folder, title, paper ("A", "B" or "none"), item
// ("Table IV") and verdict (the agreement's opening words, "" for an own study).
struct GalleryEntry {
    std::filesystem::path manifest;
    std::string dir, title, paper, item, verdict;
};

// The experiments under resultsRoot in the papers' order: paper A's items, then paper B's, each in the
// order of their numbers ("Fig. 2" before "Fig. 10"), then the own studies.
std::vector<GalleryEntry> galleryEntries(const std::filesystem::path& resultsRoot);

// A page of the results folder that a script wrote rather than vri-run (make bricks-slurm's bricks-slurm.md):
// a Markdown file there other than README.md and the pages galleryPages writes (which open with the trail
// "[Results](README.md) / "), its name a safe one (isSafeName, before ".md"). The index lists it by its
// first "# " heading (its name where it has none), after the experiments.
struct ScriptPage {
    std::string name;  // in the results folder
    std::string title;
};
// Those under resultsRoot, by name.
std::vector<ScriptPage> scriptPages(const std::filesystem::path& resultsRoot);

// The Markdown pages of those experiments (galleryEntries'), found once and shared with the viewer's pages;
// the index lists the script pages after them.
std::vector<GalleryPage> galleryPages(const std::vector<GalleryEntry>& entries, const std::vector<ScriptPage>& scripts);

// The caption of an experiment's heat maps: what they show and each one's scale, read from each
// comparison's vri-diff JSON in `dir` ("" when none has a heat map).
std::string heatMapCaption(const nlohmann::json& diffImages, const std::filesystem::path& dir);

// The warning under an experiment's tables and charts when any of its renders was timed under load ("" when
// none was).
std::string loadCaption(const nlohmann::json& steps, const std::filesystem::path& dir);

}  // namespace vri
