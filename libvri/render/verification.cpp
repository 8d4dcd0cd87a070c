#include "libvri/render/verification.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>

#include "libvri/core/cpu_renderer.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/image_compare.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/hypothesis_test.h"
#include "libvri/util/statistics.h"
#include "libvri/render/scene_card.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// statistics.h's observed order over the points with a positive error (an image equal to the reference has
// none to fit); NaN when fewer than two remain.
double orderOf(const std::vector<double>& steps, const std::vector<double>& errors) {
    std::vector<double> h, e;
    for (std::size_t i = 0; i < steps.size(); ++i)
        if (errors[i] > 0.0 && std::isfinite(errors[i])) {
            h.push_back(steps[i]);
            e.push_back(errors[i]);
        }
    return h.size() >= 2 ? observedOrder(h, e) : std::numeric_limits<double>::quiet_NaN();
}

struct Errors {
    double mean = 0, max = 0, rmse = 0;  // the worst channel's
};

Errors errorsAgainst(const Image& reference, const Image& image) {
    Errors e;
    for (const ChannelDiff& c : compareImages(reference, image, {}).channels) {
        e.mean = std::max(e.mean, c.meanAbs);
        e.max = std::max(e.max, c.maxAbs);
        e.rmse = std::max(e.rmse, c.rmse);
    }
    return e;
}

nlohmann::json toJson(const Errors& e) { return {{"mean", e.mean}, {"max", e.max}, {"rmse", e.rmse}}; }

RenderRequest atStep(const RenderRequest& base, double step, std::optional<Placement> placement = std::nullopt) {
    RenderRequest request = base;
    request.options.samplingRate = 1.0 / step;
    if (placement) request.options.placement = *placement;
    request.options.progress = false;
    return request;
}

// One card of the sweep in its own folder, the renderer run on it.
OutsideRun runOnCard(const OutsideRenderer& renderer, const SceneSetup& setup, const RenderRequest& request,
                     const fs::path& dir) {
    fs::create_directories(dir);
    auto [card, voxels] = sceneCardWithVoxels(setup, request, setup.scene.volume ? "voxels.raw" : "");
    OutputSet files;
    if (setup.scene.volume) files.add(dir / "voxels.raw", std::move(voxels));
    files.add(dir / "card.json", card.dump(2) + "\n");
    files.write();
    return runOutsideRenderer(renderer, card, dir);
}

// A renderer's frames (one image per seed) and their per-pixel moments, summed in double.
class FrameMoments {
public:
    void add(const Image& image) {
        frames_.push_back(image);
        if (n_ == 0) {
            first_ = image;
            sum_.assign(image.pixels.size(), 0.0);
            sumSquares_.assign(image.pixels.size(), 0.0);
        }
        for (std::size_t i = 0; i < sum_.size(); ++i) {
            const double v = image.pixels[i];
            sum_[i] += v;
            sumSquares_[i] += v * v;
        }
        ++n_;
    }
    int count() const { return n_; }
    std::size_t size() const { return sum_.size(); }
    double mean(std::size_t i) const { return sum_[i] / n_; }
    // The unbiased variance, 0 where rounding would make it negative.
    double variance(std::size_t i) const {
        return n_ > 1 ? std::max(0.0, (sumSquares_[i] - sum_[i] * sum_[i] / n_) / (n_ - 1)) : 0.0;
    }
    // Each frame's values, for the permutation test; upside down, each frame flipped the right way up.
    std::vector<const std::vector<float>*> values(bool flip, std::vector<Image>& flipped) const {
        std::vector<const std::vector<float>*> out;
        if (flip) {
            flipped.clear();
            for (const Image& f : frames_) flipped.push_back(flippedVertically(f));
            for (const Image& f : flipped) out.push_back(&f.pixels);
        } else {
            for (const Image& f : frames_) out.push_back(&f.pixels);
        }
        return out;
    }
    Image meanImage() const {
        Image image = first_;
        for (std::size_t i = 0; i < sum_.size(); ++i) image.pixels[i] = static_cast<float>(mean(i));
        return image;
    }

private:
    Image first_;
    std::vector<Image> frames_;
    std::vector<double> sum_, sumSquares_;
    int n_ = 0;
};

// A jittered step's bias and noise against the reference: the noise is the frames' standard deviation (RMS
// over pixels and channels); the bias the RMS of mean - reference with the noise's share removed (the mean of
// n frames has variance sigma^2 / n).
struct BiasNoise {
    double bias = 0, noise = 0;
};

BiasNoise biasAndNoise(const FrameMoments& frames, const Image& reference) {
    double squared = 0, variance = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const double d = frames.mean(i) - reference.pixels[i];
        squared += d * d;
        variance += frames.variance(i);
    }
    const double m = static_cast<double>(frames.size());
    return {std::sqrt(std::max(0.0, squared / m - variance / m / frames.count())), std::sqrt(variance / m)};
}

// What counts as no difference between two expectations: the renderer's output quantisation (half a level),
// else float32 rounding of values near 1.
double noDifferenceBelow(const std::string& quantisation) {
    if (quantisation == "8-bit") return 0.5 / 255.0;
    if (quantisation == "16-bit") return 0.5 / 65535.0;
    return 1e-6;
}

// The jitter test's permutations and level: with 999 permutations the smallest p is 0.001.
constexpr int kPermutations = 999;
constexpr double kSignificance = 0.01;

struct Finding {
    std::string name;  // the test case: "orientation", "placement", "convergence", "error floor"
    bool passed;
    std::string message;  // what was found, and what is wrong when it failed
};

std::string xmlEscaped(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

// Three significant digits: a report's numbers are measurements, not bits.
std::string number(double x) {
    if (!std::isfinite(x)) return "n/a";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

}  // namespace

VerificationReport verifyRenderer(const OutsideRenderer& renderer, const SceneSetup& setup, const RenderRequest& base,
                                  const VerificationOptions& options, const fs::path& workDir,
                                  const std::function<void(const std::string&)>& progress) {
    std::vector<double> steps = options.steps;
    std::sort(steps.begin(), steps.end(), std::greater<>());
    if (steps.size() < 3 || std::adjacent_find(steps.begin(), steps.end()) != steps.end())
        throw UsageError("--steps: expected at least 3 different steps, for an order over more than one interval");
    const Scene& scene = setup.scene;
    const Camera camera(setup.camera);

    ExactReferenceOptions exact;
    exact.tolerance = options.referenceTolerance;
    const ExactReference reference = renderExactReference(scene, camera, exact);
    const Image referenceImage = reference.image();
    double referenceBound = 0.0;
    for (const double b : reference.stats.maxStoredBound) referenceBound = std::max(referenceBound, b);
    progress("the reference: exact, tolerance " + exactNumber(options.referenceTolerance) + ", error bound " +
             number(referenceBound));

    // The sweep: the renderer's images, and vri's own at every step; with seeds, each the mean of the frames.
    const bool jittered = options.seeds > 1;
    if (options.rendererJobs < 1)
        throw Error("the renderer's runs at once (--renderer-jobs): expected at least 1, got " +
                    std::to_string(options.rendererJobs));
    std::vector<OutsideRun> runs;
    std::vector<double> ours;
    std::vector<FrameMoments> theirFrames, ourFrames;
    Image oursCoarsest;  // vri's image at the coarsest step, also the placement probe's at the base placement
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const RenderRequest request = atStep(base, steps[i]);
        validateRender(scene, camera, request.options);  // the card's step, before the renderer is run on it
        const fs::path stepDir = workDir / ("step-" + std::to_string(i + 1));
        Image mine;
        if (!jittered) {
            runs.push_back(runOnCard(renderer, setup, request, stepDir));
            mine = render(scene, camera, request.options);
        } else {
            FrameMoments theirs, mineFrames;
            OutsideRun run;
            const auto seeded = [&](int k) {
                RenderRequest r = request;
                r.options.seed = base.options.seed + static_cast<std::uint32_t>(k);  // wraps, as vri's frames do
                return r;
            };
            // The renderer's runs, options.rendererJobs at a time, each in its seed's folder; kept in seed order.
            // A run that fails is reported once the others of its batch have ended (the lowest seed's first).
            std::vector<OutsideRun> seedRuns(static_cast<std::size_t>(options.seeds));
            for (int first = 0; first < options.seeds; first += options.rendererJobs) {
                std::vector<std::future<OutsideRun>> batch;
                for (int k = first; k < std::min(options.seeds, first + options.rendererJobs); ++k)
                    batch.push_back(std::async(std::launch::async, [&, k] {
                        return runOnCard(renderer, setup, seeded(k), stepDir / ("seed-" + std::to_string(k + 1)));
                    }));
                for (std::size_t b = 0; b < batch.size(); ++b) seedRuns[first + b] = batch[b].get();
            }
            for (int k = 0; k < options.seeds; ++k) {
                OutsideRun one = std::move(seedRuns[static_cast<std::size_t>(k)]);
                theirs.add(one.image);
                mineFrames.add(render(scene, camera, seeded(k).options));
                const std::vector<double> seconds = std::move(run.wallSeconds);
                run = std::move(one);
                run.wallSeconds.insert(run.wallSeconds.begin(), seconds.begin(), seconds.end());
            }
            run.image = theirs.meanImage();
            mine = mineFrames.meanImage();
            runs.push_back(std::move(run));
            theirFrames.push_back(std::move(theirs));
            ourFrames.push_back(std::move(mineFrames));
        }
        ours.push_back(errorsAgainst(referenceImage, mine).mean);
        if (i == 0) oursCoarsest = std::move(mine);
        progress("step " + exactNumber(steps[i]) + ": rendered in " + number(runs.back().wallSeconds.front()) + " s (" +
                 runs.back().timed + ")" + (jittered ? ", " + std::to_string(options.seeds) + " seeds" : ""));
    }
    // What the renderer says of itself (the last run's stats hold what every run's do).
    const std::string quantisation = runs.back().quantisation;
    const std::string name = runs.back().renderer.value("name", renderer.command.front());
    const std::string version = runs.back().renderer.value("version", "");

    std::vector<Finding> findings;
    // Orientation, from the finest image, the nearest to the reference: upside down, it is nearer flipped.
    // The other findings then read the images the right way up, so that each names its own defect.
    const double upright = errorsAgainst(referenceImage, runs.back().image).rmse;
    const double flipped = errorsAgainst(referenceImage, flippedVertically(runs.back().image)).rmse;
    const bool upsideDown = flipped < 0.5 * upright;
    findings.push_back({"orientation", !upsideDown,
                        upsideDown ? "the image is upside down: flipped vertically it is " + number(upright / flipped) +
                                         " times nearer the reference (RMSE " + number(flipped) + " against " +
                                         number(upright) + "); row 0 must be the top of the image (docs/scene-card.md)"
                                   : "row 0 at the top, as the card asks (RMSE against the reference " +
                                         number(upright) + "; flipped " + number(flipped) + ")"});
    if (upsideDown)
        for (OutsideRun& run : runs) run.image = flippedVertically(run.image);

    nlohmann::json rows = nlohmann::json::array();
    std::vector<double> theirs, theirsMax;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const Errors their = errorsAgainst(referenceImage, runs[i].image);
        theirs.push_back(their.mean);
        theirsMax.push_back(their.max);
        rows.push_back({{"step", steps[i]},
                        {"renderer", toJson(their)},
                        {"vri", {{"mean", ours[i]}}},
                        {"wall_seconds", runs[i].wallSeconds},
                        {"timed", runs[i].timed}});
        progress("step " + exactNumber(steps[i]) + ": mean error " + number(their.mean) + " (vri " + number(ours[i]) +
                 ")");
    }

    // A jittered renderer: bias and noise per step, and its expectation against vri's jittered frames.
    nlohmann::json jitterRecord;
    if (jittered) {
        const double margin = noDifferenceBelow(quantisation);
        std::vector<std::vector<double>> pValues(steps.size());
        std::vector<double> all;
        bool anyNoise = false;
        for (std::size_t i = 0; i < steps.size(); ++i) {
            const FrameMoments& t = theirFrames[i];
            const FrameMoments& o = ourFrames[i];
            const int width = runs[i].image.width, height = runs[i].image.height, channels = runs[i].image.channels;
            for (std::size_t p = 0; p < t.size(); ++p) {
                // Upside down, the renderer's pixel (x, y) is vri's (x, height - 1 - y).
                std::size_t q = p;
                if (upsideDown) {
                    const std::size_t pixel = p / channels, row = pixel / width;
                    q = ((height - 1 - row) * width + pixel % width) * channels + p % channels;
                }
                anyNoise = anyNoise || t.variance(p) > 0.0;
                pValues[i].push_back(welchP(t.mean(p), t.variance(p), o.mean(q), o.variance(q), options.seeds, margin));
            }
            all.insert(all.end(), pValues[i].begin(), pValues[i].end());
        }
        const std::size_t rejected = benjaminiHochbergRejections(all, options.falseDiscoveryRate);
        std::sort(all.begin(), all.end());
        const double threshold = rejected > 0 ? all[rejected - 1] : -1.0;
        std::size_t worst = 0, worstCount = 0;
        double smallestP = 1.0;
        std::size_t smallestAt = 0;
        for (std::size_t i = 0; i < steps.size(); ++i) {
            std::vector<Image> theirsUpright, unused;
            const double p = permutationP(theirFrames[i].values(upsideDown, theirsUpright),
                                          ourFrames[i].values(false, unused), kPermutations, 0x5eed0000 + i);
            rows[i]["permutation_p"] = p;
            if (p < smallestP) {
                smallestP = p;
                smallestAt = i;
            }
            const std::size_t count = static_cast<std::size_t>(
                std::ranges::count_if(pValues[i], [&](double p) { return p <= threshold; }));
            if (count > worstCount) {
                worst = i;
                worstCount = count;
            }
            const BiasNoise theirs = biasAndNoise(theirFrames[i], upsideDown ? flippedVertically(referenceImage) : referenceImage);
            const BiasNoise mine = biasAndNoise(ourFrames[i], referenceImage);
            rows[i]["renderer"]["bias_rms"] = theirs.bias;
            rows[i]["renderer"]["noise_rms"] = theirs.noise;
            rows[i]["vri"]["bias_rms"] = mine.bias;
            rows[i]["vri"]["noise_rms"] = mine.noise;
            rows[i]["differing"] = count;
        }
        // The decision is the permutation test's (exact whatever the pixels' distributions), at level
        // kSignificance over the steps (Bonferroni); the per-pixel tests say where the images differ.
        const double level = kSignificance / static_cast<double>(steps.size());
        const bool differs = smallestP <= level;
        const std::string test =
            "a permutation test of the " + std::to_string(options.seeds) + " frames against vri's " +
            std::to_string(options.seeds) + " jittered frames at each step, " + std::to_string(kPermutations) +
            " permutations, level " + number(kSignificance) + " over the steps; smallest p " + number(smallestP) +
            " at step " + exactNumber(steps[smallestAt]) + "; where: Welch's t-test per pixel and channel, " +
            "Benjamini-Hochberg at q = " + number(options.falseDiscoveryRate) + " over all " +
            std::to_string(all.size()) + " tests, differences below " + number(margin) + " counted as none";
        std::string message;
        bool passed = false;
        if (!anyNoise) {
            message = "the " + std::to_string(options.seeds) +
                      " frames of every card are identical: the renderer does not jitter, or does not take the "
                      "card's seed (method.jitter.seed, or {seed} on its command line)";
        } else if (differs) {
            message = "its frames are not distributed as the card's jittered Riemann sum's (" + test + "; " +
                      (rejected > 0 ? std::to_string(rejected) + " pixel-channels differ, most at step " +
                                          exactNumber(steps[worst])
                                    : std::string("no pixel-channel differs on its own: the difference is spread")) +
                      "): is the first sample uniform on [0, 1) of a step past the entry (docs/scene-card.md), and "
                      "the rest of the sum the card's?";
        } else {
            passed = true;
            message = "its frames are distributed as the card's jittered Riemann sum's, as far as " +
                      std::to_string(options.seeds) + " seeds can tell (" + test + "; " + std::to_string(rejected) +
                      " pixel-channels differ)";
        }
        findings.push_back({"jitter", passed, message});
        jitterRecord = {{"seeds", options.seeds},
                        {"false_discovery_rate", options.falseDiscoveryRate},
                        {"no_difference_below", margin},
                        {"tests", all.size()},
                        {"differing", rejected},
                        {"permutations", kPermutations},
                        {"significance", kSignificance},
                        {"smallest_p", smallestP},
                        {"differs", differs}};
    }

    // Placement, from the coarsest image: placements differ most at a long step; a jittered renderer's is
    // the jitter's, tested above.
    nlohmann::json placements = nlohmann::json::object();
    std::string placementUsed = "jittered";
    if (!jittered) {
        Placement best = Placement::EntryAlign;
        double bestRmse = std::numeric_limits<double>::infinity(), secondRmse = bestRmse;
        for (const Placement p :
             {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign, Placement::EntryExitAlignCorner}) {
            const Image vri =
                p == base.options.placement ? oursCoarsest : render(scene, camera, atStep(base, steps.front(), p).options);
            const double rmse = errorsAgainst(vri, runs.front().image).rmse;
            placements[std::string(placementName(p))] = rmse;
            if (rmse < bestRmse) {
                secondRmse = bestRmse;
                bestRmse = rmse;
                best = p;
            } else {
                secondRmse = std::min(secondRmse, rmse);
            }
        }
        const bool clear = secondRmse > 1.25 * bestRmse;
        std::string placementText = std::string(placementName(best)) + " (RMSE " + number(bestRmse) + " against vri's " +
                                    std::string(placementName(best)) + " image at step " + exactNumber(steps.front()) +
                                    "; the next placement " + number(secondRmse) + (clear ? ")" : ", too close to tell)");
        const bool placementWrong = options.placement && clear && best != *options.placement;
        findings.push_back({"placement", !placementWrong,
                            placementWrong ? "uses placement " + placementText + ", but the card asks for " +
                                                 std::string(placementName(*options.placement))
                                           : "placement " + placementText});
        placementUsed = placementName(best);
    }

    // Convergence: the order over the finest steps, unless the error stops falling there, a floor: the
    // error fell over the first interval and no longer over the last. The order is then fitted over the
    // leading intervals where it still fell, and the floor is reported with what it may come from.
    const std::size_t n = steps.size();
    const std::vector<double> fineSteps(steps.end() - 3, steps.end()), fineErrors(theirs.end() - 3, theirs.end());
    std::vector<double> pairwise;  // the order over each interval, coarse to fine
    for (std::size_t i = 0; i + 1 < n; ++i)
        pairwise.push_back(orderOf({steps[i], steps[i + 1]}, {theirs[i], theirs[i + 1]}));
    const bool floor = pairwise.front() >= 0.8 * options.minOrder && !(pairwise.back() >= 0.5 * options.minOrder);
    std::vector<double> fitSteps = fineSteps, fitErrors = fineErrors;
    if (floor) {
        std::size_t falling = 0;
        while (falling < pairwise.size() && pairwise[falling] >= 0.5 * options.minOrder) ++falling;
        fitSteps.assign(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(falling + 1));
        fitErrors.assign(theirs.begin(), theirs.begin() + static_cast<std::ptrdiff_t>(falling + 1));
    } else if (!(orderOf(fineSteps, fineErrors) >= 0.5 * options.minOrder)) {  // nothing falls: the whole sweep
        fitSteps = steps;
        fitErrors = theirs;
    }
    const double order = orderOf(fitSteps, fitErrors);
    std::vector<double> fitMax, fitOurs;  // over the same steps: the largest error's order, and vri's own
    for (const double h : fitSteps) {
        const auto i = static_cast<std::size_t>(std::find(steps.begin(), steps.end(), h) - steps.begin());
        fitMax.push_back(theirsMax[i]);
        fitOurs.push_back(ours[i]);
    }
    const double maxOrder = orderOf(fitSteps, fitMax);
    const double ourOrder = orderOf(fitSteps, fitOurs);
    // No positive error to fit (NaN) passes only where the images are the reference itself.
    const bool converges = std::isnan(order) ? theirs.back() == 0.0 : order >= options.minOrder;
    std::string convergence = "observed order " + number(order) + " of the mean error over steps " +
                              exactNumber(fitSteps.front()) + " to " + exactNumber(fitSteps.back()) +
                              " (largest error: " + number(maxOrder) +
                              "; vri's own at these steps: " + number(ourOrder) + ")";
    if (!converges)
        convergence +=
            ", below " + number(options.minOrder) +
            (order < 0.25 ? ": the error does not fall with the step. Does the renderer take the card's "
                            "step, and correct the opacity for it (alpha = 1 - exp(-tau dx), tau per world unit, "
                            "dx the step in world units)? Or does another error, larger than the step's, hide it?"
                          : ": the renderer converges more slowly than a Riemann sum should");
    findings.push_back({"convergence", converges, convergence});
    std::string floorText =
        "none: at the finest step the error is " + number(theirs.back()) + ", vri's own " + number(ours.back());
    if (floor) {
        const bool eightBit = quantisation == "8-bit" && theirs.back() <= 2.0 / 255.0;
        floorText = "the error stops falling near " + number(theirs.back()) + " from step " +
                    exactNumber(fitSteps.back()) + " (order " + number(pairwise.back()) +
                    " over the last interval; vri's "
                    "own Riemann sum at step " +
                    exactNumber(steps.back()) + ": " + number(ours.back()) + "): " +
                    (eightBit ? "the image is 8-bit, which alone leaves up to 1/510 = 0.00196 per channel"
                              : "not the step's: a quantised transfer function or texture, the interpolation, or an "
                                "approximate opacity correction");
    }
    findings.push_back({"error floor", true, floorText});

    VerificationReport report;
    report.passed = std::ranges::all_of(findings, [](const Finding& f) { return f.passed; });
    nlohmann::json list = nlohmann::json::array();
    for (const Finding& f : findings) list.push_back({{"name", f.name}, {"passed", f.passed}, {"message", f.message}});
    report.record = {
        {"renderer", {{"name", name}, {"version", version}, {"command", renderer.command}}},
        {"reference",
         {{"method", "exact"}, {"tolerance", options.referenceTolerance}, {"error_bound_max", referenceBound}}},
        {"steps", rows},
        {"order", order},
        {"order_max_error", maxOrder},
        {"vri_order", ourOrder},
        {"min_order", options.minOrder},
        {"floor", floor ? nlohmann::json(theirs.back()) : nlohmann::json()},
        {"quantisation", quantisation},
        {"placement", placementUsed},
        {"jitter", jitterRecord},
        {"placement_rmse", placements},
        {"upside_down", upsideDown},
        {"findings", list},
        {"passed", report.passed}};

    std::string& md = report.markdown;
    // No heading of its own: the report stands alone and also sits inside the results gallery's sections.
    md = "**Verification of " + name + (version.empty() ? "" : " " + version) + ": " +
         (report.passed ? "PASSED" : "FAILED") + "**, against vri's exact reference (error bound " +
         number(referenceBound) + ").\n\n| finding | | |\n|---|---|---|\n";
    for (const Finding& f : findings)
        md += "| " + f.name + " | " + (f.passed ? "pass" : "**FAIL**") + " | " + f.message + " |\n";
    md += std::string("\n| step (voxels) | mean error | largest error | vri's mean error | seconds |") +
          (jittered ? " bias (RMS) | noise per frame (RMS) | vri's bias | vri's noise | p (permutation) | pixels differing |" : "") +
          "\n|--:|--:|--:|--:|--:|" + (jittered ? "--:|--:|--:|--:|--:|--:|" : "") + "\n";
    for (const nlohmann::json& r : rows) {
        std::vector<double> seconds = r["wall_seconds"].get<std::vector<double>>();
        std::nth_element(seconds.begin(), seconds.begin() + static_cast<std::ptrdiff_t>(seconds.size() / 2),
                         seconds.end());
        md += "| " + exactNumber(r["step"].get<double>()) + " | " + number(r["renderer"]["mean"]) + " | " +
              number(r["renderer"]["max"]) + " | " + number(r["vri"]["mean"]) + " | " +
              number(seconds[seconds.size() / 2]) + " (" + r["timed"].get<std::string>() + ") |";
        if (jittered)
            md += " " + number(r["renderer"]["bias_rms"]) + " | " + number(r["renderer"]["noise_rms"]) + " | " +
                  number(r["vri"]["bias_rms"]) + " | " + number(r["vri"]["noise_rms"]) + " | " +
                  number(r["permutation_p"]) + " | " + std::to_string(r["differing"].get<std::size_t>()) + " |";
        md += "\n";
    }

    std::string& xml = report.junit;
    const auto failures = std::ranges::count_if(findings, [](const Finding& f) { return !f.passed; });
    xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"vri-verify " + xmlEscaped(name) +
          "\" tests=\"" + std::to_string(findings.size()) + "\" failures=\"" + std::to_string(failures) + "\">\n";
    for (const Finding& f : findings) {
        xml += "  <testcase classname=\"vri-verify\" name=\"" + xmlEscaped(f.name) + "\">";
        xml += f.passed ? "<system-out>" + xmlEscaped(f.message) + "</system-out>"
                        : "<failure message=\"" + xmlEscaped(f.message) + "\"/>";
        xml += "</testcase>\n";
    }
    xml += "</testsuite>\n";
    return report;
}

}  // namespace vri
