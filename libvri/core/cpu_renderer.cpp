#include "libvri/core/cpu_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <glm/vector_relational.hpp>
#include <glm/geometric.hpp>

#include "libvri/core/early_termination.h"
#include "libvri/core/fixed_step_ray.h"
#include "libvri/core/frame_average.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/simd_march.h"
#include "libvri/core/simd_target.h"
#include "libvri/core/sparse_sampler.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/printable.h"
#include "libvri/util/progress.h"

namespace vri {

std::string_view precisionName(Precision p) { return p == Precision::Double ? "double" : "float"; }

Precision parsePrecision(std::string_view name, const std::string& what) {
    if (name == "double") return Precision::Double;
    if (name == "float") return Precision::Float;
    throw Error(what + ": unknown precision '" + std::string(name) + "' (expected double or float)");
}

bool packetMethod(const RenderOptions& options) {
    return options.precision == Precision::Float &&
           (options.integrator == Integrator::Riemann || options.integrator == Integrator::Composite ||
            options.integrator == Integrator::Preintegrated);
}

void parseSimd(std::string_view name, const std::string& what, RenderOptions& options) {
    options.simd = name != "off";
    options.simdTarget.clear();
    if (name == "on" || name == "off") return;
    options.simdTarget = simdTargetNamed(name);
    if (options.simdTarget.empty())
        throw Error(what + ": unknown value '" + printable(name) + "' (expected on, off or a SIMD target this CPU and " +
                    "build have: " + simdTargetList() + ")");
}

void parseEarlyTermination(const std::string& text, const std::string& what, RenderOptions& options) {
    options.earlyTermination = options.terminationBound = 0.0;
    if (text == "auto") {
        options.terminationBound = kAutoTerminationBound;
        return;
    }
    const bool bound = text.rfind("auto:", 0) == 0;
    const std::optional<double> v = parseNumber(bound ? text.substr(5) : text);
    if (!v || !(*v >= 0.0 && *v < 1.0) || (bound && !(*v > 0.0)))
        throw Error(what + ": expected a transparency in [0, 1), 'auto' or 'auto:BOUND' with a bound in (0, 1), got '" +
                    printable(text) + "'");
    (bound ? options.terminationBound : options.earlyTermination) = *v;
}

Box Scene::box() const {
    if (sparse) return gridBox(sparse->dims, sparse->spacing, sparse->origin, convention);
    return volume ? volumeBox(*volume, convention) : field->box;
}

glm::dvec3 Scene::dims() const { return glm::dvec3(sparse ? sparse->dims : volume ? volume->dims : field->dims); }

namespace {

struct Counters {
    std::atomic<std::uint64_t> raysHit{0}, samplesPlaced{0}, samplesEvaluated{0}, raysTerminated{0};
    std::mutex mutex;  // guards the rest
    AdaptiveCounts adaptive;
    SimpsonRange simpsonRange;
    double terminationLeftOut = 0.0;
};


// Paper A's fixed-step placements, each sample standing for a segment of the ray (Riemann, composite).
template <class Real, class Sampler>
RayAccumulator<Real> marchSamples(const TextureRay<Real>& ray, const Sampler& sample, const OccupancyGrid* occupancy,
                                  const GridIndexing& indexMap, const glm::vec<3, Real>& eyeU, const glm::vec<3, Real>& dims,
                                  const TransferFunction& tf, const RenderOptions& opt,
                                  const TerminationRule& termination, std::optional<Real> jitter, MarchCounts& counts) {
    RayAccumulator<Real> acc;
    const EmissionModel emission = tf.emission();
    FixedStepRay<Real> march(ray, opt, eyeU, dims, indexMap, jitter);
    const std::int64_t count = march.schedule.count;
    const Real ert = termination.threshold<Real>(march.dx, count);
    std::size_t segment = 0;  // the transfer function's last bracket
    std::int64_t k = 0;
    while (k < count) {
        if (occupancy && march.mayBeEmpty(k)) {
            k = march.skipEmpty(*occupancy, k);
            if (k == count) break;
        }
        acc.add(opt.integrator, emission, tf(sample(march.position(k)), segment), march.dx);
        ++counts.samplesEvaluated;
        ++k;
        if (acc.transparency < ert) break;
    }
    counts.samplesPlaced += static_cast<std::uint64_t>(k);
    if (k < count) counts.terminated(termination.leftOut(acc.transparency, march.dx, count));
    return acc;
}

// Pre-integration: sample k of paper A's placement stands for the segment from half a step before it to
// half a step after (as in composite), whose integral the table gives from the scalars at its ends (and
// at the sample itself, the midpoint, for order 2). The segments share their ends, so a ray of n
// samples reads n + 1 scalars (2n + 1 for order 2). Every segment is looked up: an entry interpolates
// its neighbours in the table, so a segment in an empty brick need not look up exactly zero.
template <class Real, class Sampler>
RayAccumulator<Real> marchSegments(const TextureRay<Real>& ray, const Sampler& sample, const glm::vec<3, Real>& eyeU,
                                   const glm::vec<3, Real>& dims, const PreintegrationTable& table,
                                   const RenderOptions& opt, std::optional<Real> jitter, MarchCounts& counts) {
    RayAccumulator<Real> acc;
    const FixedStepSamples<Real> march(ray, opt, eyeU, dims, jitter);
    const std::int64_t count = march.schedule.count;
    if (count == 0) return acc;
    const Real lengthRatio = march.dx / static_cast<Real>(table.segmentLength());
    const bool secondOrder = table.order() == 2;
    Real front = sample(march.segmentStart(0));
    for (std::int64_t k = 0; k < count; ++k) {
        const Real back = sample(march.segmentStart(k + 1));
        const Real delta = secondOrder ? sample(march.position(k)) - Real(0.5) * (front + back) : Real(0);
        acc.addSegment(table(front, back, delta), lengthRatio);
        front = back;
    }
    counts.samplesPlaced += static_cast<std::uint64_t>(count);
    counts.samplesEvaluated += static_cast<std::uint64_t>(count);
    return acc;
}

// True when [a, b] of an index-space ray lies in empty bricks only. Conservative: it gives up
// (false) rather than loop on a brick exit that rounding leaves on the wrong side.
bool emptyAlong(const OccupancyGrid& occupancy, const OccupancyGrid::Ray& ray, double a, double b) {
    double t = a;
    for (int visits = 0; visits < 64; ++visits) {
        const auto brick = occupancy.visit(ray, t);
        if (!brick.empty) return false;
        if (brick.tExit >= b) return true;
        if (!(brick.tExit > t)) return false;
        t = brick.tExit;
    }
    return false;
}

// Paper B's Simpson methods along one ray, parametrised in voxels of ray (adaptive_simpson.h).
template <class Real, class Sampler>
AdaptiveResult<Real> integrateSimpson(const TextureRay<Real>& ray, const Sampler& sample,
                                      const OccupancyGrid* occupancy, const GridIndexing& indexMap,
                                      const glm::vec<3, Real>& dims, const TransferFunction& tf,
                                      const AdaptiveSimpsonRay<Real>& method, AdaptiveCounts& counts,
                                      std::vector<AdaptiveTry>* log) {
    using Vec = glm::vec<3, Real>;
    const Vec along = ray.exit - ray.entry;
    const Real length = glm::length(along * dims);  // voxels, as paper A's placements count them
    if (!(length > Real(0))) return {};
    const Vec du = along / length;  // texture units per voxel of ray
    const Real worldPerVoxel = static_cast<Real>(ray.worldLength / static_cast<double>(length));
    const bool colourTimesExtinction = tf.emission() == EmissionModel::ColourTimesExtinction;
    std::size_t segment = 0;  // the transfer function's last bracket
    const auto evaluate = [&](Real v) {
        const TransferFunctionSample<Real> x = tf(sample(ray.entry + v * du), segment);
        const Real kappa = x.tau * worldPerVoxel;
        const Real weight = colourTimesExtinction ? kappa : worldPerVoxel;
        return RayPoint<Real>{kappa, x.r * weight, x.g * weight, x.b * weight};
    };
    if (!occupancy) return method.integrate(length, evaluate, [](double, double) { return false; }, counts, log);
    const OccupancyGrid::Ray indexRay(glm::dvec3(ray.entry) * indexMap.scale - indexMap.offset,
                                      glm::dvec3(du) * indexMap.scale);
    const auto knownEmpty = [&](double a, double b) { return emptyAlong(*occupancy, indexRay, a, b); };
    return method.integrate(length, evaluate, knownEmpty, counts, log);
}

// Calls renderTile(x0, y0, x1, y1, counts, adaptive, range) for every tile of `area` (pixels of the
// camera's image), in parallel, and adds up what the tiles counted.
template <class RenderTile>
void forEachTile(const RenderOptions& opt, const PixelRegion& area, Counters& counters, const RenderTile& renderTile) {
    const int tile = opt.tileSize;
    const int tilesX = (area.width + tile - 1) / tile, tilesY = (area.height + tile - 1) / tile;
    Progress progress("render", static_cast<std::uint64_t>(tilesX) * tilesY, opt.progress);
    tbb::parallel_for(tbb::blocked_range2d<int>(0, tilesY, 1, 0, tilesX, 1), [&](const auto& tiles) {
        MarchCounts counts;
        AdaptiveCounts adaptive;
        SimpsonRange range{counters.simpsonRange.limit};
        for (int ty = tiles.rows().begin(); ty < tiles.rows().end(); ++ty)
            for (int tx = tiles.cols().begin(); tx < tiles.cols().end(); ++tx) {
                renderTile(area.x + tx * tile, area.y + ty * tile, area.x + std::min((tx + 1) * tile, area.width),
                           area.y + std::min((ty + 1) * tile, area.height), counts, adaptive, range);
                progress.advance(1);
            }
        counters.raysHit += counts.raysHit;
        counters.samplesPlaced += counts.samplesPlaced + adaptive.pointsUsed;
        counters.samplesEvaluated += counts.samplesEvaluated + adaptive.pointsEvaluated;
        counters.raysTerminated += counts.raysTerminated;
        const std::lock_guard lock(counters.mutex);
        counters.terminationLeftOut = std::max(counters.terminationLeftOut, counts.terminationLeftOut);
        if (isSimpson(opt.integrator)) {
            counters.adaptive += adaptive;
            counters.simpsonRange.merge(range);
        }
    });
}

template <class Real, class Sampler>
void renderWith(const Scene& scene, const Sampler& sample, const OccupancyGrid* occupancy, const GridIndexing& indexMap,
                const Camera& camera, const RenderOptions& opt, Image& image, Counters& counters,
                std::vector<AdaptiveTry>* rayLog, const PreintegrationTable* table) {
    using Vec = glm::vec<3, Real>;
    const Box box = scene.box();
    const Vec dims(scene.dims());
    const Vec eyeU(box.toTexture(camera.eye()));
    const TransferFunction& tf = scene.transferFunction;
    const bool simpson = isSimpson(opt.integrator);
    const TerminationRule termination(tf, opt, box, scene.dims());
    const AdaptiveSimpsonRay<Real> method(simpsonParameters(opt), termination.simpsonThreshold<Real>());
    const PixelRegion area = renderedRegion(opt.region, camera);
    forEachTile(opt, area, counters, [&](int x0, int y0, int x1, int y1, MarchCounts& counts, AdaptiveCounts& adaptive,
                                         SimpsonRange& range) {
        for (int py = y0; py < y1; ++py)
            for (int px = x0; px < x1; ++px) {
                float* out = &image.at(px - area.x, py - area.y, 0);
                const auto clipped = pixelRay<Real>(camera, box, px, py);
                if (!clipped) continue;
                const TextureRay<Real>& ray = *clipped;
                if (ray.worldLength > 0) ++counts.raysHit;
                if (simpson) {
                    const bool logged = rayLog && opt.logPixel == glm::ivec2(px, py);
                    const AdaptiveResult<Real> r = integrateSimpson(ray, sample, occupancy, indexMap, dims, tf, method,
                                                                    adaptive, logged ? rayLog : nullptr);
                    out[0] = static_cast<float>(r.r);
                    out[1] = static_cast<float>(r.g);
                    out[2] = static_cast<float>(r.b);
                    out[3] = static_cast<float>(r.alpha);
                    if (r.terminated) counts.terminated(termination.simpsonLeftOut(r.transparency));
                    range.addRay(static_cast<double>(r.largestStepDepth));
                } else {
                    const std::optional<Real> jitter =
                        opt.jitter ? std::optional<Real>(static_cast<Real>(jitterFraction(px, py, opt.seed)))
                                   : std::nullopt;
                    const RayAccumulator<Real> acc =
                        table ? marchSegments(ray, sample, eyeU, dims, *table, opt, jitter, counts)
                              : marchSamples(ray, sample, occupancy, indexMap, eyeU, dims, tf, opt, termination,
                                             jitter, counts);
                    out[0] = static_cast<float>(acc.r);
                    out[1] = static_cast<float>(acc.g);
                    out[2] = static_cast<float>(acc.b);
                    out[3] = static_cast<float>(acc.alpha());
                }
            }
    });
}

// setupSpent: what building empty-space structures took in this call (the rest was reused).
template <class Real>
void renderScene(const Scene& scene, const Camera& camera, const RenderOptions& opt, Image& image,
                 Counters& counters, RenderStats& stats, OccupancyCache& cache, double& setupSpent) {
    std::vector<AdaptiveTry>* log = opt.logPixel ? &stats.rayLog : nullptr;
    std::optional<PreintegrationTable> table;
    if (opt.integrator == Integrator::Preintegrated) {
        const auto start = std::chrono::steady_clock::now();
        table.emplace(scene.transferFunction, preintegrationSegmentLength(scene, opt), opt.preintegrationSize,
                      opt.preintegrationOrder);
        stats.preintegration = {table->size(), table->order(), table->segmentLength(), table->check(scene.transferFunction)};
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats.setupSeconds += seconds;
        setupSpent += seconds;
    }
    const PreintegrationTable* lookup = table ? &*table : nullptr;
    if (!scene.volume && !scene.sparse) {
        renderWith<Real>(scene, LinearFieldSampler<Real>{}, nullptr, GridIndexing{}, camera, opt, image, counters,
                         log, lookup);
        return;
    }
    const OccupancyGrid* occupancy = nullptr;
    if (opt.skipEmptySpace && !table) {
        const auto grid = scene.sparse ? cache.grid(scene.sparse, scene.convention, scene.transferFunction)
                                       : cache.grid(scene.volume, scene.convention, scene.transferFunction);
        occupancy = &grid.structure;
        stats.setupSeconds += grid.buildSeconds;
        stats.setupReused = grid.reused;
        if (!grid.reused) setupSpent += grid.buildSeconds;
        stats.emptyBrickFraction = occupancy->emptyFraction();
    }
    const GridIndexing indexMap(glm::ivec3(scene.dims()), scene.convention);
    if (scene.sparse) {  // the scalar path whatever opt.simd says: the packet engine reads dense volumes only
        dispatchVoxelType(scene.sparse->type, [&](auto voxel) {
            const SparseGridSampler<decltype(voxel), Real> sampler(*scene.sparse, scene.convention);
            renderWith<Real>(scene, sampler, occupancy, indexMap, camera, opt, image, counters, log, lookup);
        });
        return;
    }
    if (opt.simd && PacketScene::supports(scene, opt)) {
        const StencilBricks* stencils = nullptr;
        if (opt.skipEmptySpace && !table) {
            const auto entry =
                cache.stencilBricks(scene.volume, scene.convention, scene.transferFunction, rayOctants(camera));
            stencils = &entry.structure;
            stats.setupSeconds += entry.buildSeconds;
            if (!entry.reused) setupSpent += entry.buildSeconds;
            stats.setupReused = stats.setupReused && entry.reused;
        }
        const PacketScene packets(scene, camera, stencils, opt, lookup);
        useSimdTarget(opt.simdTarget);
        stats.simdTarget = packetTargetName();
        if (stats.simdTarget == "AVX2" && packets.readsByVoxelLoads()) stats.voxelLoads = voxelLoadsName(packets.voxelLoads);
        forEachTile(opt, renderedRegion(opt.region, camera), counters,
                    [&](int x0, int y0, int x1, int y1, MarchCounts& counts, AdaptiveCounts&, SimpsonRange&) {
            marchPackets(packets, x0, y0, x1, y1, image, counts);
        });
        return;
    }
    const Volume& volume = *scene.volume;
    dispatchVoxelType(volume.type, [&](auto voxel) {
        const GridSampler<decltype(voxel), Real> sampler(volume, scene.convention);
        renderWith<Real>(scene, sampler, occupancy, indexMap, camera, opt, image, counters, log, lookup);
    });
}

}  // namespace

PixelRegion renderedRegion(const std::optional<PixelRegion>& region, const Camera& camera) {
    if (region && !region->inside(camera.width(), camera.height()))
        throw Error("the region " + region->text() + " (X,Y,WIDTH,HEIGHT) is not inside the " +
                    std::to_string(camera.width()) + "x" + std::to_string(camera.height()) + " image");
    return region.value_or(PixelRegion::whole(camera.width(), camera.height()));
}

AdaptiveParameters simpsonParameters(const RenderOptions& opt) {
    AdaptiveParameters p = opt.adaptive;
    if (opt.integrator == Integrator::Simpson) {
        p.h0 = p.hMin = p.hMax = 1.0 / opt.samplingRate;
        p.coupling = Coupling::Coupled;
    } else {
        p.coupling = opt.integrator == Integrator::Coupled ? Coupling::Coupled : Coupling::Decoupled;
    }
    return p;
}

void validateRender(const Scene& scene, const Camera& camera, const RenderOptions& options) {
    if (!(options.samplingRate > 0.0) || !std::isfinite(options.samplingRate))
        throw Error("sampling rate must be positive and finite (step h = 1 / rate > 0), got " +
                    std::to_string(options.samplingRate));
    if (options.tileSize < 1) throw Error("tile size must be at least 1");
    if (!scene.volume && !scene.sparse && !scene.field) throw Error("scene has neither a volume nor an analytic field");
    // A named target where the packets cannot run would be recorded as asked for and never run (with "on"
    // the scalar path runs, and the stats say so).
    if (options.simd && !options.simdTarget.empty() && packetMethod(options) && !PacketScene::supports(scene, options))
        throw Error("--simd " + options.simdTarget + ": the SIMD packets need a dense volume (not --storage sparse) of 4 "
                    "to 2^31 - 1 bytes with at least 2 voxels along x, and a transfer function of at most " +
                    std::to_string(PacketScene::kMaxPoints) + " points; this scene is not one: leave --simd on");
    if (!(options.earlyTermination >= 0.0 && options.earlyTermination < 1.0))
        throw Error("early termination threshold must be in [0, 1), got " + std::to_string(options.earlyTermination));
    if (!(options.terminationBound >= 0.0 && options.terminationBound < 1.0))
        throw Error("early termination bound must be in [0, 1), got " + std::to_string(options.terminationBound));
    if (options.earlyTermination > 0.0 && options.terminationBound > 0.0)
        throw Error("early termination takes a transparency threshold or a bound, not both");
    if (options.terminationBound > 0.0 && isSimpson(options.integrator)) {
        // The Simpson methods' K (early_termination.h) grows as exp(tau_max h / 48): a step without an
        // h_max may leave it beyond double's range, and then no ray could end.
        const TerminationRule rule(scene.transferFunction, options, scene.box(), scene.dims());
        const bool none = options.precision == Precision::Double ? !(rule.simpsonThreshold<double>() > 0.0)
                                                                 : !(rule.simpsonThreshold<float>() > 0.0f);
        if (none) {
            const double hMax = simpsonParameters(options).hMax;
            throw Error("--early-termination auto:" + exactNumber(options.terminationBound) + ": " +
                        std::string(integratorName(options.integrator)) + " with steps up to " +
                        (std::isfinite(hMax) ? exactNumber(hMax) + " voxels" : std::string("the whole ray (no h_max)")) +
                        " at this transfer function's largest tau cannot bound what an ended ray leaves out (" +
                        exactNumber(rule.simpsonFactor()) + " times its transparency): give --h-max or a transparency threshold");
        }
    }
    const bool preintegrated = options.integrator == Integrator::Preintegrated;
    // A looked-up segment's colour is not bounded by C_max times its alpha (the table interpolates colour
    // and depth apart), so early_termination.h's bounds do not hold for it.
    if (preintegrated && (options.earlyTermination > 0.0 || options.terminationBound > 0.0))
        throw Error("early termination: not available for the preintegrated method (its bound does not hold for "
                    "interpolated table entries)");
    if (options.jitter && (isSimpson(options.integrator)))
        throw Error("jitter: applies to the placed fixed-step methods (riemann, composite, preintegrated), not " +
                    std::string(integratorName(options.integrator)));
    if (options.frames < 1) throw Error("frames must be at least 1, got " + std::to_string(options.frames));
    if (options.frames > 1 && !options.jitter) throw Error("frames: averaging frames needs jitter (each frame a seed)");
    if (preintegrated) {
        if (options.preintegrationSize < PreintegrationTable::kMinSize ||
            options.preintegrationSize > PreintegrationTable::kMaxSize)
            throw Error("pre-integration table size must be in [" + std::to_string(PreintegrationTable::kMinSize) +
                        ", " + std::to_string(PreintegrationTable::kMaxSize) + "], got " +
                        std::to_string(options.preintegrationSize));
        if (options.preintegrationOrder != 1 && options.preintegrationOrder != 2)
            throw Error("pre-integration order must be 1 or 2, got " + std::to_string(options.preintegrationOrder));
        if (options.logPixel) throw Error("the logged ray: applies to coupled and decoupled only");
    }
    const glm::dvec3 dims = scene.dims();
    // The longest ray crosses |dims| voxels; keep its sample count well inside an int64 and a float.
    if (options.samplingRate * glm::length(dims) > 1e9)
        throw Error("sampling rate " + exactNumber(options.samplingRate) + " per voxel (step " +
                    exactNumber(1.0 / options.samplingRate) +
                    " voxels) would put more than 1e9 samples on a ray through this volume");
    if (options.integrator == Integrator::Coupled || options.integrator == Integrator::Decoupled)
        validate(options.adaptive);
    // The Simpson methods' sample budget, refused up front as the rate above is: a ray takes at most
    // length / h_min steps (each tried at most log2(h_max / h_min) + 1 times), so h_min bounds the work
    // whatever the tolerance. Their position t accumulates step by step, so in float a step below about
    // 2^-23 of the ray's length would no longer advance t at all and the ray would never end.
    if (isSimpson(options.integrator)) {
        const double hMin = simpsonParameters(options).hMin;
        const bool inFloat = options.precision == Precision::Float;
        const double maxSteps = inFloat ? 4194304.0 : 1e9;
        if (!(glm::length(dims) / hMin <= maxSteps))
            throw Error((options.integrator == Integrator::Simpson ? "step " : "h_min ") + exactNumber(hMin) +
                        " would allow more than " + (inFloat ? "2^22 steps on a ray through this volume in float "
                                                               "precision (a shorter step no longer advances the ray)"
                                                             : "1e9 steps on a ray through this volume"));
    }
    const PixelRegion area = renderedRegion(options.region, camera);
    if (options.logPixel && !area.contains(options.logPixel->x, options.logPixel->y))
        throw Error("the logged pixel " + std::to_string(options.logPixel->x) + "," +
                    std::to_string(options.logPixel->y) + " is outside the " +
                    (options.region ? "region " + area.text() + " of the " : std::string()) +
                    std::to_string(camera.width()) + "x" + std::to_string(camera.height()) + " image");
    // A float render converts the transfer function to float: a value beyond float's range becomes
    // infinity, and every sample of the segments next to it Inf or NaN (Inf * 0). Nothing the ray
    // does can save it, so it is refused here; overflows that depend on the ray are found after the
    // render (nonfinite_pixels.h).
    if (options.precision == Precision::Float) {
        const auto& points = scene.transferFunction.points();
        for (std::size_t i = 0; i < points.size(); ++i) {
            const TransferFunctionPoint& p = points[i];
            const double largest = std::max({p.r, p.g, p.b, p.tau});
            if (largest > std::numeric_limits<float>::max())
                throw Error("transfer function point " + std::to_string(i) + " holds " + exactNumber(largest) +
                            ", beyond the range of float (" + exactNumber(std::numeric_limits<float>::max()) +
                            "), the precision of this render: use double precision");
        }
    }
    if (scene.convention == GridConvention::NodeCentred && glm::any(glm::lessThan(dims, glm::dvec3(2.0))))
        throw Error("the node-centred convention needs at least 2 voxels along every axis (the box would be flat)");
}

double preintegrationSegmentLength(const Scene& scene, const RenderOptions& options) {
    // Entry Exit Align Corner counts the step on dims - 1 voxels (placement.h), the others on dims.
    const double voxels = scene.dims().x - (options.placement == Placement::EntryExitAlignCorner ? 1.0 : 0.0);
    return scene.box().size().x / voxels / options.samplingRate;
}

Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats,
             OccupancyCache* cache) {
    validateRender(scene, camera, options);
    if (options.frames > 1)
        return averageFrames(options, stats, [&](const RenderOptions& frame, RenderStats* frameStats) {
            return render(scene, camera, frame, frameStats, cache);
        });
    const PixelRegion area = renderedRegion(options.region, camera);
    Image image(area.width, area.height);
    Counters counters;
    counters.simpsonRange.limit = simpsonStepDepthLimit(simpsonParameters(options).accepted);
    RenderStats local;
    OccupancyCache once;  // without a cache, this frame builds its own grid
    OccupancyCache& grids = cache ? *cache : once;
    const auto start = std::chrono::steady_clock::now();
    double setupSpent = 0.0;
    if (options.precision == Precision::Double)
        renderScene<double>(scene, camera, options, image, counters, local, grids, setupSpent);
    else
        renderScene<float>(scene, camera, options, image, counters, local, grids, setupSpent);
    // The frame's own work: what this call spent building empty-space structures is setup, reported on its own.
    local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - setupSpent;
    local.rays = static_cast<std::uint64_t>(image.width) * image.height;
    local.raysHit = counters.raysHit;
    local.samplesPlaced = counters.samplesPlaced;
    local.samplesEvaluated = counters.samplesEvaluated;
    local.raysTerminated = counters.raysTerminated;
    local.terminationLeftOut = counters.terminationLeftOut;
    if (isSimpson(options.integrator)) {
        local.adaptive = counters.adaptive;
        local.simpsonRange = counters.simpsonRange;
    }
    // The arena's concurrency ignores a tbb::global_control limit; the limit is what the workers get.
    local.threads = static_cast<int>(std::min<std::size_t>(
        tbb::this_task_arena::max_concurrency(),
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
    local.nonfinite = findNonFinitePixels(image);
    if (stats) *stats = local;
    return image;
}

}  // namespace vri
