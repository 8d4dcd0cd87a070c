#include "libvri/core/render_option_table.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libvri/core/exact_ray.h"
#include "libvri/core/simd_target.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/parse.h"

namespace vri {

namespace {

constexpr unsigned kBothTools = unsigned(RenderTool::Render) | unsigned(RenderTool::Reference);
constexpr unsigned kRenderOnly = unsigned(RenderTool::Render);
constexpr unsigned kCpu = 1u << unsigned(Backend::Cpu), kVulkan = 1u << unsigned(Backend::Vulkan);
constexpr unsigned kBothBackends = kCpu | kVulkan;

bool adaptive(const RenderRequest& r) {
    return !r.exact && (r.options.integrator == Integrator::Coupled || r.options.integrator == Integrator::Decoupled);
}

bool flagValue(const std::string& text, const std::string& where) {
    if (text == "true" || text == "false") return text == "true";
    throw Error(where + ": expected true or false, got '" + text + "'");
}

bool preintegrated(const RenderRequest& r) { return !r.exact && r.options.integrator == Integrator::Preintegrated; }

std::string noDefault(const RenderRequest&) { return {}; }
void noSetting(const RenderRequest&, std::vector<Setting>&) {}

// The rows, in the order of --help and of the experiment reader's list of keys.
const RenderOptionRow kRows[] = {
    {"--method", "method", "", OptionValueKind::Text,
     "riemann (paper A eq. 5), composite (opacity-corrected), simpson (uniform steps of --step), coupled or decoupled "
     "(paper B's adaptive Simpson), preintegrated (a table of each step's segment integral, --preint-size), exact "
     "(vri-reference's method, with a per-pixel error bound); vri-reference: exact or riemann (paper B's reference)",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.exact = text == "exact";
         if (r.exact) return;
         if (r.tool == RenderTool::Reference && text != "riemann")
             throw Error(where + ": unknown method '" + text + "' (expected exact or riemann)");
         r.options.integrator = parseIntegrator(text, where);
     },
     [](const RenderRequest& r) { return std::string(r.exact ? "exact" : integratorName(r.options.integrator)); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         s.push_back({"method", std::string(r.exact ? "exact" : integratorName(r.options.integrator))});
     }},
    {"--placement", "placement", "", OptionValueKind::Text, "eye, entry, entry-exit or entry-exit-corner (paper A)", "",
     "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.placement = parsePlacement(text, where);
     },
     [](const RenderRequest& r) { return std::string(placementName(r.options.placement)); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (!r.exact && !isSimpson(r.options.integrator))
             s.push_back({"placement", std::string(placementName(r.options.placement))});
     }},
    {"--step", "step", "h", OptionValueKind::Number,
     "step h in voxels (riemann, composite, simpson; vri-reference: riemann)", "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.samplingRate = 1.0 / parsePositive(text, where);
     },
     [](const RenderRequest& r) { return exactNumber(1.0 / r.options.samplingRate); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (r.exact || adaptive(r)) return;
         s.push_back({"sampling_rate", r.options.samplingRate});
         s.push_back({"step_voxels", 1.0 / r.options.samplingRate});
     }},
    {"--rate", "rate", "r", OptionValueKind::Number, "sampling rate in samples per voxel (= 1 / step)", "", "--step",
     kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.samplingRate = parsePositive(text, where);
     },
     noDefault, noSetting},  // recorded with --step
    {"--precision", "precision", "", OptionValueKind::Text, "double or float (the Vulkan backend: float only, its default)",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.precision = parsePrecision(text, where);
     },
     [](const RenderRequest& r) { return std::string(precisionName(r.options.precision)); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         s.push_back({"precision", std::string(r.exact ? "double" : precisionName(r.options.precision))});
     }},
    {"--simd", "simd", "simd-", OptionValueKind::Text,
     "on: float riemann, composite and preintegrated on packets of rays, one per SIMD lane (bitwise equal to off), on "
     "the best target this CPU has or VRI_SIMD_TARGET's; a target's name (AVX3, AVX2, SSE4, ...) to run on that one; "
     "off: the scalar path. --method exact: the target of its batched Gauss rules (tolerance 1e-10 up; every target "
     "gives the same bits), off refused (experiment files: `lower` is a run per target below the best)",
     "", "", kBothTools, kCpu,
     [](const std::string& text, const std::string& where, RenderRequest& r) { parseSimd(text, where, r.options); },
     [](const RenderRequest& r) {
         return r.options.simd ? (r.options.simdTarget.empty() ? std::string("on") : r.options.simdTarget) : "off";
     },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (!r.exact) s.push_back({"simd", r.options.simd});  // the exact method has no scalar twin to record
         // A forced target: the packets', or the exact method's Gauss batches'.
         if (r.options.simd && !r.options.simdTarget.empty()) s.push_back({"simd_target", r.options.simdTarget});
     },
     [](std::string_view text) -> std::optional<std::vector<std::string>> {
         if (text != "lower") return std::nullopt;
         std::vector<std::string> lower = availableSimdTargets();
         lower.erase(lower.begin());  // the best is `on`'s
         return lower;
     }},
    {"--early-termination", "early_termination", "ert", OptionValueKind::Text,
     "stop rays whose transparency drops below this (0 = off), or 'auto' (once the rest can change no channel by more "
     "than 1e-4; 'auto:BOUND' for another bound), the most left out in the stats",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         parseEarlyTermination(text, where, r.options);
     },
     [](const RenderRequest& r) { return exactNumber(r.options.earlyTermination); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (r.exact) return;
         if (r.options.terminationBound > 0.0) s.push_back({"early_termination.bound", r.options.terminationBound});
         else s.push_back({"early_termination", r.options.earlyTermination});
     }},
    {"--preint-size", "preint_size", "n", OptionValueKind::Count,
     "preintegrated: entries of the table per scalar axis, from 2 to 1024 (its error against direct evaluation is in "
     "the stats)",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.preintegrationSize =
             parseCount(text, where, PreintegrationTable::kMinSize, PreintegrationTable::kMaxSize);
     },
     [](const RenderRequest& r) { return std::to_string(r.options.preintegrationSize); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (preintegrated(r)) s.push_back({"preint_size", static_cast<long long>(r.options.preintegrationSize)});
     }},
    {"--preint-order", "preint_order", "o", OptionValueKind::Count,
     "preintegrated: 1 (the scalar linear along a segment) or 2 (quadratic through the sample at its midpoint: "
     "a second table of the derivative in the midpoint's deviation)",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.preintegrationOrder = parseCount(text, where, 1, 2);
     },
     [](const RenderRequest& r) { return std::to_string(r.options.preintegrationOrder); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (preintegrated(r)) s.push_back({"preint_order", static_cast<long long>(r.options.preintegrationOrder)});
     }},
    {"--jitter", "jitter", "jitter-", OptionValueKind::Flag,
     "riemann, composite, preintegrated: put each ray's first sample at a fraction in [0, 1) of the step past the "
     "entry, hashed from the pixel and --seed",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) { r.options.jitter = flagValue(text, where); },
     noDefault,
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (!r.options.jitter) return;  // unjittered records stay as they were
         s.push_back({"jitter", true});
         s.push_back({"seed", static_cast<long long>(r.options.seed)});
         s.push_back({"frames", static_cast<long long>(r.options.frames)});
     }},
    {"--seed", "seed", "seed", OptionValueKind::Count, "--jitter's seed, from 0 to 2^31 - 1", "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.seed = static_cast<std::uint32_t>(parseCount(text, where, 0, std::numeric_limits<int>::max()));
     },
     [](const RenderRequest& r) { return std::to_string(r.options.seed); }, noSetting},  // recorded with --jitter
    {"--frames", "frames", "f", OptionValueKind::Count,
     "--jitter: the mean of N frames (at most 1000), frame f jittered with seed + f", "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.frames = parseCount(text, where, 1, kMaxFrames);
     },
     [](const RenderRequest& r) { return std::to_string(r.options.frames); }, noSetting},  // recorded with --jitter
    {"--repeat", "repeat", "x", OptionValueKind::Count,
     "render N times (at most 1000) for timing: the stats give every wall time and their median, and any image that "
     "differs from the first is an error",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.repeat = parseCount(text, where, 1, kMaxFrames);
     },
     [](const RenderRequest& r) { return std::to_string(r.repeat); }, noSetting},  // in the timing record
    // Paper B's adaptive Simpson (coupled, decoupled); the exact method's tolerance per piece.
    {"--tolerance,--eps", "eps", "eps", OptionValueKind::Number,
     "error tolerance eps at the step h0 (exact: per transfer-function piece of a ray, default 1e-7; vri-reference: "
     "default 1e-13)",
     "adaptive", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.adaptive.tolerance = r.exactTolerance = parseNonNegative(text, where);
     },
     [](const RenderRequest& r) {
         return exactNumber(r.tool == RenderTool::Reference ? r.exactTolerance : r.options.adaptive.tolerance);
     },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (r.exact) s.push_back({"tolerance", r.exactTolerance});
         else if (adaptive(r)) s.push_back({"tolerance", r.options.adaptive.tolerance});
     }},
    {"--max-error", "max_error", "maxerr", OptionValueKind::Number,
     "exact: the largest per-pixel error bound wanted; the tolerance is tightened (from --tolerance, else from E) "
     "by renders of a quarter-size pilot (from 128 pixels a side, without --region), then of the image, until "
     "every pixel's bound is at most E; the accepted render is the output's first frame, and the stats record the "
     "tolerance found and every render of the search",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) { r.maxError = parsePositive(text, where); },
     noDefault,
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (r.exact && r.maxError) s.push_back({"max_error", *r.maxError});
     }},
    {"--h0", "h0", "h0-", OptionValueKind::Number, "initial step", "adaptive", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.adaptive.h0 = parsePositive(text, where);
     },
     [](const RenderRequest& r) { return exactNumber(r.options.adaptive.h0); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (adaptive(r)) s.push_back({"h0_voxels", r.options.adaptive.h0});
     }},
    {"--h-min", "h_min", "hmin", OptionValueKind::Number, "smallest step (taken whatever the error)", "adaptive", "",
     kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.adaptive.hMin = parsePositive(text, where);
     },
     [](const RenderRequest& r) { return exactNumber(r.options.adaptive.hMin); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (adaptive(r)) s.push_back({"h_min_voxels", r.options.adaptive.hMin});
     }},
    {"--h-max", "h_max", "hmax", OptionValueKind::Text, "largest step, or 'none'", "adaptive", "", kRenderOnly,
     kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.adaptive.hMax = parseLimit(text, where);
     },
     [](const RenderRequest& r) {
         return std::isfinite(r.options.adaptive.hMax) ? exactNumber(r.options.adaptive.hMax) : std::string("none");
     },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (!adaptive(r)) return;
         const double h = r.options.adaptive.hMax;
         s.push_back({"h_max_voxels", std::isfinite(h) ? SettingValue(h) : SettingValue(std::string("none"))});
     }},
    {"--accepted-value", "accepted", "", OptionValueKind::Text, "richardson (D + (D - S)/15) or paper (D + |D - S|/15)",
     "adaptive", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.adaptive.accepted = parseAcceptedValue(text, where);
     },
     [](const RenderRequest& r) { return std::string(acceptedValueName(r.options.adaptive.accepted)); },
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (adaptive(r)) s.push_back({"accepted_value", std::string(acceptedValueName(r.options.adaptive.accepted))});
     }},
    // The experiment plan adds --log <run>-ray.csv.
    {"--log-ray", "log_ray", "ray", OptionValueKind::Text, "record every step try along pixel X,Y's ray", "adaptive",
     "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.logPixel = parsePixel(text, where);
     },
     noDefault, noSetting},
    {"--backend", "backend", "", OptionValueKind::Text, "cpu (the raycaster of libvri) or vulkan (compute shaders, float)",
     "", "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) { r.backend = parseBackend(text, where); },
     [](const RenderRequest& r) { return std::string(r.backend == Backend::Vulkan ? "vulkan" : "cpu"); },
     noSetting},  // the stats say which backend ran
    {"--device", "device", "dev", OptionValueKind::Text,
     "Vulkan device: an index of --list-devices or part of a name (default: the first)", "", "", kRenderOnly, kVulkan,
     [](const std::string& text, const std::string&, RenderRequest& r) { r.device = text; }, noDefault, noSetting},
    {"--interpolation", "interpolation", "", OptionValueKind::Text,
     "Vulkan: shader (grid_sampler.h's trilinear formula in float) or sampler (the device's 3D texture filtering)", "",
     "", kRenderOnly, kVulkan,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.interpolation = parseInterpolation(text, where);
     },
     [](const RenderRequest& r) { return std::string(interpolationName(r.interpolation)); }, noSetting},
    {"--warm-up", "warm_up", "w", OptionValueKind::Count,
     "render N untimed frames first, one jittered frame each with --frames (at most 1000: caches, clocks, a GPU's "
     "pipelines)",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.warmUp = parseCount(text, where, 0, kMaxFrames);
     },
     [](const RenderRequest& r) { return std::to_string(r.warmUp); }, noSetting},  // in the timing record
    {"--no-skip-empty", "", "", OptionValueKind::Flag, "march through empty space too (the image does not change)", "",
     "", kRenderOnly, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         r.options.skipEmptySpace = !flagValue(text, where);
     },
     noDefault,
     [](const RenderRequest& r, std::vector<Setting>& s) {
         if (!r.exact) s.push_back({"skip_empty_space", r.options.skipEmptySpace});
     }},
    // Command line only: an experiment asks for tiles (`tiles:`), and its planner writes the regions.
    {kRegionFlag, "", "", OptionValueKind::Text,
     "render only the pixels X,Y,WIDTH,HEIGHT of the --size image (x right, y down from the top row), each bit for bit "
     "as in the whole image; the outputs hold the region (vri-merge-tiles joins them)",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) {
         const glm::ivec4 v = parseRegion(text, where);
         r.options.region = PixelRegion{v.x, v.y, v.z, v.w};
     },
     noDefault, noSetting},  // the stats record the region on its own: the settings are the whole image's
    {"--clamp", "clamp", "clamp-", OptionValueKind::Flag,
     "clamp each pixel's colour and alpha to [0, 1] after the render (the stats count what was outside first); off "
     "for accuracy studies",
     "", "", kBothTools, kBothBackends,
     [](const std::string& text, const std::string& where, RenderRequest& r) { r.clamp = flagValue(text, where); },
     noDefault, [](const RenderRequest& r, std::vector<Setting>& s) { s.push_back({"clamp", r.clamp}); }},
};

const RenderOptionRow& row(std::string_view flag) {
    return *std::find_if(std::begin(kRows), std::end(kRows), [&](const RenderOptionRow& r) { return r.flag() == flag; });
}

}  // namespace

RenderRequest::RenderRequest(RenderTool t) : tool(t) {
    if (tool == RenderTool::Reference) {  // the exact method, or paper B's reference: Riemann h = 0.01, entry, double
        exact = true;
        exactTolerance = ExactReferenceOptions{}.tolerance;
        options.samplingRate = 1.0 / 0.01;
    } else {
        exactTolerance = 1e-7;
        options.samplingRate = 1.0 / 0.5;
    }
}

bool RenderRequest::wasGiven(std::string_view flag) const { return std::ranges::find(given, flag) != given.end(); }

ExactReferenceOptions RenderRequest::exactOptions() const {
    ExactReferenceOptions o;
    o.tolerance = exactTolerance;
    o.skipEmptySpace = options.skipEmptySpace;
    o.region = options.region;
    o.progress = options.progress;
    o.simdTarget = options.simdTarget;
    return o;
}

std::span<const RenderOptionRow> renderOptionTable() { return kRows; }

std::string_view renderOptionGroupHelp(std::string_view group) {
    return group == "adaptive" ? "coupled and decoupled (paper B), steps in voxels" : "";
}

const RenderOptionRow* findRenderOption(std::string_view key) {
    const auto found = std::find_if(std::begin(kRows), std::end(kRows), [&](auto& r) { return !r.key.empty() && r.key == key; });
    return found == std::end(kRows) ? nullptr : found;
}

void finishRenderRequest(RenderRequest& r) {
    for (const std::string_view flag : r.given) {
        const RenderOptionRow& given = row(flag);
        if (!given.takenBy(r.tool)) throw Error(std::string(flag) + ": not an option of this tool");
        if (!given.excludes.empty() && r.wasGiven(given.excludes))
            throw Error(std::string(flag) + ": cannot be given with " + std::string(given.excludes));
    }
    if (r.exact && r.wasGiven("--simd") && !r.options.simd)
        throw Error("--simd off: the exact method's Gauss rules have no scalar twin; name a target (SCALAR is "
                    "Highway's one-lane fallback)");
    if (r.tool == RenderTool::Reference) {
        if (r.exact && r.wasGiven("--step")) throw Error("--step applies to --method riemann only");
        if (!r.exact && r.wasGiven("--tolerance")) throw Error("--tolerance applies to --method exact only");
        if (!r.exact && r.wasGiven("--simd")) throw Error("--simd applies to --method exact only (the reference Riemann sum is double)");
    } else if (r.exact) {
        if (r.backend != Backend::Cpu) throw Error("--method exact: runs on --backend cpu only");
        if (r.wasGiven("--precision") && r.options.precision != Precision::Double)
            throw Error("--precision: --method exact is double only");
        if (r.wasGiven("--step") || r.wasGiven("--rate")) throw Error("--step, --rate: --method exact has no step");
        if (r.wasGiven("--early-termination"))
            throw Error("--early-termination: --method exact ends rays by its --tolerance");
        if (r.options.logPixel) throw Error("--log-ray: applies to coupled and decoupled only");
    }
    if (!adaptive(r))
        for (const std::string_view flag : {"--h0", "--h-min", "--h-max", "--accepted-value"})
            if (r.wasGiven(flag)) throw Error(std::string(flag) + ": applies to --method coupled and decoupled only");
    if (r.exact && r.wasGiven("--placement"))
        throw Error("--placement: --method exact takes no samples to place");
    if (!preintegrated(r))
        for (const std::string_view flag : {"--preint-size", "--preint-order"})
            if (r.wasGiven(flag)) throw Error(std::string(flag) + ": applies to --method preintegrated only");
    if (r.options.jitter && (r.exact || isSimpson(r.options.integrator)))
        throw Error("--jitter: applies to --method riemann, composite and preintegrated only");
    if (!r.options.jitter)
        for (const std::string_view flag : {"--seed", "--frames"})
            if (r.wasGiven(flag)) throw Error(std::string(flag) + ": needs --jitter");
    if (preintegrated(r) && r.wasGiven("--early-termination"))
        throw Error("--early-termination: not available for --method preintegrated (its bound does not hold for "
                    "interpolated table entries)");
    if (r.maxError && !r.exact)
        throw Error("--max-error applies to --method exact only (the only method with a per-pixel error bound)");
    if (r.exact && !(r.exactTolerance > 0.0))
        throw Error("--tolerance: must be > 0 for --method exact, got " + exactNumber(r.exactTolerance));
    // A forced target with nothing to run on would be recorded in options.simd_target as if it had run.
    if (!r.exact && r.wasGiven("--simd") && !r.options.simdTarget.empty() && !packetMethod(r.options))
        throw Error("--simd " + r.options.simdTarget + ": the SIMD packets run float riemann, composite and "
                    "preintegrated only, not " + std::string(integratorName(r.options.integrator)) + " in " +
                    std::string(precisionName(r.options.precision)));
    if (r.exact && r.wasGiven("--simd") && !r.options.simdTarget.empty() && !r.maxError &&
        r.exactTolerance < ExactRay::kGaussTolerance)
        throw Error("--simd " + r.options.simdTarget + ": the exact method's SIMD Gauss batches run from --tolerance " +
                    exactNumber(ExactRay::kGaussTolerance) + " up; at " + exactNumber(r.exactTolerance) + " none runs");
    for (const std::string_view flag : r.given)
        if ((row(flag).backends & (1u << unsigned(r.backend))) == 0)
            throw Error(std::string(flag) + ": needs --backend " + (r.backend == Backend::Cpu ? "vulkan" : "cpu"));
    if (r.backend == Backend::Vulkan && !r.wasGiven("--precision")) r.options.precision = Precision::Float;
    // A warm-up frame is one jittered frame (RenderJob::warmUpFrame); a timed one averages --frames of them.
    const long long rendered = r.warmUp + static_cast<long long>(r.repeat) * r.options.frames;
    if (rendered > kMaxRenderedFrames)
        throw Error("--warm-up " + std::to_string(r.warmUp) + " + --repeat " + std::to_string(r.repeat) + " x --frames " +
                    std::to_string(r.options.frames) + " asks for " + std::to_string(rendered) +
                    " frames; at most " + std::to_string(kMaxRenderedFrames) + " in one run");
}

std::vector<Setting> settingsRecord(const RenderRequest& request) {
    std::vector<Setting> settings;
    for (const RenderOptionRow& r : kRows) r.record(request, settings);
    settings.push_back({"tile_size", static_cast<long long>(request.exact ? request.exactOptions().tileSize
                                                                           : request.options.tileSize)});
    return settings;
}

}  // namespace vri
