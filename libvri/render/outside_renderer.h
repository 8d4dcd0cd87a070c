#pragma once
// An outside renderer run from a scene card (vri-outside, experiment runs with `renderer:`): the card and
// the voxels written to a work folder, the renderer's command run with its placeholders filled in (no
// shell reads a word), and its image and statistics read back in vri's terms, so that vri-diff,
// vri-tabulate and the charts take the run like one of vri's own (docs/outside-renderers.md).
//
// The command's placeholders: {card} (the card's path), {voxels} (the raw voxels, or empty for an analytic
// field), {output} (where the renderer writes its image), {stats} (where it may write its statistics),
// {step} (the step in voxels), {seed} (a jittered card's seed, else 0), {width}, {height}, {vri_bin} (the
// folder of vri's tools: vri-peer-vtk is an outside renderer too); {{ and }} stand for braces.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/core/image.h"

namespace vri {

struct OutsideRenderer {
    std::vector<std::string> command;  // argv with placeholders; command[0] is looked up in PATH as execvp does
    std::string imageFormat = "exr";   // what {output} ends in: exr (RGBA float), png (8 or 16 bit RGBA), f32 (raw)
    std::string name;                  // the record's name when the renderer's stats give none; empty: the program's
    double timeoutSeconds = 0.0;       // stop it (SIGTERM, then SIGKILL) past this; 0: no limit
};

// The minimal statistics record a renderer may write to {stats} (docs/outside-renderers.md):
// {"format": "vri-outside-stats", "version": 1, "renderer": {"name", "version"}, "timing": {"what": "frame",
// "wall_seconds": [...]}, "image": {"quantisation"}, "settings": {...}, "notes": [...]}.
inline constexpr std::string_view kOutsideStatsFormat = "vri-outside-stats";

struct OutsideRun {
    Image image;                      // RGBA, the card's size, premultiplied as the card asks
    std::string quantisation;         // "float32", "16-bit", "8-bit" (from the file)
    nlohmann::json renderer;          // the record's "renderer": name, version, command, executable and its digest, ...
    std::vector<double> wallSeconds;  // the renderer's own frame times, else the process's one time
    std::string timed;                // "frame" (the renderer's own timing) or "process" (vri's of the whole command)
};

// The words of `command` with the placeholders replaced; throws vri::Error naming an unknown or unclosed one.
std::vector<std::string> expandPlaceholders(const std::vector<std::string>& command,
                                            const std::map<std::string, std::string, std::less<>>& values);

// Runs `renderer` on the card (already written at workDir/card.json, with its voxels beside it) and reads
// back what it wrote; throws vri::Error with one line naming the renderer and what went wrong (it could not
// start, failed, wrote no image, an image of another size or without alpha, an unreadable stats file).
OutsideRun runOutsideRenderer(const OutsideRenderer& renderer, const nlohmann::json& card,
                              const std::filesystem::path& workDir);

// An image in one of the formats a renderer may write: .exr or .png through OpenImageIO (RGBA; 8- and
// 16-bit PNG scaled to [0, 1]), or .f32, raw little-endian float32 RGBA, row 0 at the top, of `width` x `height`.
Image readOutsideImage(const std::filesystem::path& path, int width, int height, std::string& quantisation);

}  // namespace vri
