#pragma once
// A renderer's verification report (vri-verify): Etiene et al.'s method, verification by the order of
// convergence, asked paper A's question. The renderer runs on scene cards at a sweep of steps. Each image
// is compared with vri's certified reference: the exact method, whose error bound is far below the errors
// measured. The report gives:
//  - the observed order of convergence of the mean and the largest error, fitted over the finest steps;
//  - the error floor, where the error stops falling with the step, set against vri's own Riemann sum at the
//    same step, and where the floor comes from when the data say (8-bit output);
//  - which of paper A's four placements the renderer uses: its coarsest image against vri's at each;
//  - whether the image is upside down (row 0 must be the top);
//  - for a jittered renderer (seeds > 1: each card run once per seed), its bias against its noise at each
//    step, and whether its expectation is that of the card's jittered Riemann sum, per pixel: Welch's t-test
//    of the renderer's frames against vri's own jittered frames, Benjamini-Hochberg over every pixel, channel
//    and step. Convergence is then that of the mean of the frames, and the placement is the jitter's.
// Each finding is a pass or a failure with a message that names what is wrong. The report is written as
// Markdown, JSON and JUnit XML; its exit code is for a CI job to gate on.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/core/render_option_table.h"
#include "libvri/render/outside_renderer.h"
#include "libvri/render/scene_setup.h"

namespace vri {

struct VerificationOptions {
    std::vector<double> steps;         // in voxels, at least 3, each used for one card
    double minOrder = 0.75;            // the observed order below which convergence fails
    double referenceTolerance = 1e-9;  // the exact method's quadrature tolerance per piece
    // The placement the renderer must use; none: it is identified and reported, not checked.
    std::optional<Placement> placement;
    // Jittered cards: each step's card run with seeds base.seed, base.seed + 1, ... (the base request must
    // ask for jitter, one frame); 1: the renderer is deterministic.
    int seeds = 1;
    // With seeds: how many of a step's cards the renderer runs on at once, each its own process. A browser
    // renderer waits about half its time (vtk.js in Chromium: 2.1 s of CPU in 4.2 s).
    int rendererJobs = 1;
    double falseDiscoveryRate = 0.001;  // q of the Benjamini-Hochberg procedure over every pixel test
};

struct VerificationReport {
    nlohmann::json record;  // every number of the report
    std::string markdown;
    std::string junit;  // JUnit XML: one test case per finding
    bool passed = false;
};

// Runs the sweep in `workDir` (a folder per card) and returns the report; `progress` is told each step
// ("step 0.5: 0.41 s"). Throws vri::Error when the renderer cannot be run or writes no image.
VerificationReport verifyRenderer(const OutsideRenderer& renderer, const SceneSetup& setup, const RenderRequest& base,
                                  const VerificationOptions& options, const std::filesystem::path& workDir,
                                  const std::function<void(const std::string&)>& progress);

}  // namespace vri
