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

#include "libvri/core/brick_layers.h"
#include "libvri/core/brick_sampler.h"
#include "libvri/core/early_termination.h"
#include "libvri/core/fixed_step_ray.h"
#include "libvri/core/frame_average.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/simd_march.h"
#include "libvri/core/simd_target.h"
#include "libvri/core/sparse_sampler.h"
#include "libvri/util/progress.h"

namespace vri {

namespace {

struct RenderCounters {
    std::mutex mutex;  // guards the rest
    MarchCounts march;  // the adaptive methods' points included in its samples
    AdaptiveCounts adaptive;
    SimpsonRange simpsonRange;
};

// Paper A's fixed-step placements, each sample standing for a segment of the ray (Riemann, composite). With
// a brick's sampler, the run of samples the brick owns, summed from transmittance 1 (a layer, brick_layers.h),
// and its place among the ray's bricks in `brickPlace`.
template <class Real, class Sampler>
RayAccumulator<Real> marchSamples(const TextureRay<Real>& ray, const Sampler& sample, const OccupancyGrid* occupancy,
                                  const GridIndexing& indexMap, const glm::vec<3, Real>& eyeU,
                                  const glm::vec<3, Real>& dims, const TransferFunction& tf, const RenderOptions& opt,
                                  const TerminationRule& termination, std::optional<Real> jitter, MarchCounts& counts,
                                  int* brickPlace = nullptr) {
    RayAccumulator<Real> acc;
    const EmissionModel emission = tf.emission();
    FixedStepRay<Real> march(ray, opt, eyeU, dims, indexMap, jitter);
    const std::int64_t count = march.schedule.count;
    std::int64_t k = 0, end = count;
    if constexpr (kIsBrickSampler<Sampler>) {
        const BrickSamples run =
            sample.ownedSamples(march.du, count, [&](std::int64_t i) { return march.position(i); });
        k = run.begin;
        end = run.end;
        *brickPlace = run.order;
    }
    const std::int64_t first = k;
    const Real ert = termination.threshold<Real>(march.dx, count);
    std::size_t segment = 0;  // the transfer function's last bracket
    while (k < end) {
        if (occupancy && march.mayBeEmpty(k)) {
            k = march.skipEmpty(*occupancy, k);
            if (k >= end) break;
        }
        acc.add(opt.integrator, emission, tf(sample(march.position(k)), segment), march.dx);
        ++counts.samplesEvaluated;
        ++k;
        if (acc.transparency < ert) break;
    }
    counts.samplesPlaced += static_cast<std::uint64_t>(k - first);
    if (k < end) counts.terminated(termination.leftOut(acc.transparency, march.dx, count));
    return acc;
}

// Pre-integration: sample k of paper A's placement stands for the segment from half a step before it to
// half a step after (as in composite), whose integral the table gives from the scalars at its ends (and
// at the sample itself, the midpoint, for order 2). The segments share their ends, so a ray of n
// samples reads n + 1 scalars (2n + 1 for order 2).
//
// Empty space, `occupancy` being the table's own (OccupancyGrid over PreintegrationTable::isInvisible): a
// segment whose two ends lie in empty bricks looks up exactly 0, which adds nothing (addSegment), so it is
// skipped, bit for bit. Its ends lie one step apart, so in one brick or in two that touch, whose scalar
// ranges (margins included) overlap: then the table reads zeros between them too. A step longer than a
// brick could join two bricks that do not touch, and such a ray skips nothing.
template <class Real, class Sampler>
RayAccumulator<Real> marchSegments(const TextureRay<Real>& ray, const Sampler& sample, const OccupancyGrid* occupancy,
                                   const GridIndexing& indexMap, const glm::vec<3, Real>& eyeU,
                                   const glm::vec<3, Real>& dims, const PreintegrationTable& table,
                                   const RenderOptions& opt, std::optional<Real> jitter, MarchCounts& counts) {
    RayAccumulator<Real> acc;
    // The walk's positions are the segments' ends: boundary k at the sample schedule's t(k) - half a step,
    // k = 0 .. count, each in a brick that skipEmpty() looks up.
    FixedStepRay<Real> ends(ray, opt, eyeU, dims, indexMap, jitter);
    const FixedStepSamples<Real> march = ends;  // the samples, as placed (a copy: `ends` walks the boundaries)
    const std::int64_t count = march.schedule.count;
    if (count == 0) return acc;
    const double stepVoxels = glm::length(glm::dvec3(march.du) * indexMap.scale) * static_cast<double>(march.schedule.tIncr);
    if (!(stepVoxels < OccupancyGrid::kBrick)) occupancy = nullptr;
    SampleSchedule<Real> boundaries = march.schedule;
    boundaries.tStart -= march.halfStep();
    boundaries.count += 1;
    ends.schedule = boundaries;
    const Real lengthRatio = march.dx / static_cast<Real>(table.segmentLength());
    const bool secondOrder = table.order() == 2;
    const std::vector<double>& levels = table.checkedDeltas();  // order 2's deviations, counted (MarchCounts)
    std::int64_t k = 0, lookedUp = 0;
    bool haveFront = false;
    Real front{};
    while (k < count) {
        if (occupancy && ends.mayBeEmpty(k)) {
            // Boundaries k .. next - 1 lie in empty bricks: the segments between them look up 0.
            const std::int64_t next = ends.skipEmpty(*occupancy, k);
            if (next - 1 > k) {
                k = next - 1;
                haveFront = false;
                if (k >= count) break;
            }
        }
        if (!haveFront) front = sample(march.segmentStart(k));
        const Real back = sample(march.segmentStart(k + 1));
        const Real delta = secondOrder ? sample(march.position(k)) - Real(0.5) * (front + back) : Real(0);
        if (acc.addSegment(table(front, back, delta), lengthRatio) && secondOrder) {
            const Real size = std::abs(delta);
            counts.largestDelta = std::max(counts.largestDelta, static_cast<double>(size));
            ++counts.lookupsBeyond[0];
            for (std::size_t level = 0; level < levels.size() && size > static_cast<Real>(levels[level]); ++level)
                ++counts.lookupsBeyond[level + 1];
        }
        front = back;
        haveFront = true;
        ++lookedUp;
        ++k;
    }
    counts.samplesPlaced += static_cast<std::uint64_t>(count);
    counts.samplesEvaluated += static_cast<std::uint64_t>(lookedUp);
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
void forEachTile(const RenderOptions& opt, const PixelRegion& area, RenderCounters& counters,
                 const RenderTile& renderTile) {
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
        counts.samplesPlaced += adaptive.pointsUsed;
        counts.samplesEvaluated += adaptive.pointsEvaluated;
        const std::lock_guard lock(counters.mutex);
        counters.march.merge(counts);
        if (isSimpson(opt.integrator)) {
            counters.adaptive += adaptive;
            counters.simpsonRange.merge(range);
        }
    });
}

template <class Real, class Sampler>
void renderWith(const Scene& scene, const Sampler& sample, const OccupancyGrid* occupancy, const GridIndexing& indexMap,
                const Camera& camera, const RenderOptions& opt, Image& image, RenderCounters& counters,
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
                    int brickPlace = 0;
                    const RayAccumulator<Real> acc =
                        table ? marchSegments(ray, sample, occupancy, indexMap, eyeU, dims, *table, opt, jitter, counts)
                              : marchSamples(ray, sample, occupancy, indexMap, eyeU, dims, tf, opt, termination, jitter,
                                             counts, &brickPlace);
                    out[0] = static_cast<float>(acc.r);
                    out[1] = static_cast<float>(acc.g);
                    out[2] = static_cast<float>(acc.b);
                    out[3] = static_cast<float>(acc.alpha());
                    if constexpr (kIsBrickSampler<Sampler>) out[4] = static_cast<float>(brickPlace);
                }
            }
    });
}

// setupSpent: what building empty-space structures took in this call (the rest was reused).
template <class Real>
void renderScene(const Scene& scene, const Camera& camera, const RenderOptions& opt, Image& image,
                 RenderCounters& counters, RenderStats& stats, OccupancyCache& cache, double& setupSpent) {
    std::vector<AdaptiveTry>* log = opt.logPixel ? &stats.rayLog : nullptr;
    const PreintegrationTable* lookup = nullptr;  // the table of --method preintegrated, kept across frames
    if (opt.integrator == Integrator::Preintegrated) {
        const auto entry = cache.preintegration(scene.volume, scene.convention, scene.transferFunction,
                                                preintegrationSegmentLength(scene, opt), opt.preintegrationSize,
                                                opt.preintegrationOrder);
        lookup = &entry.structure.table;
        stats.preintegration = RenderStats::Preintegration{.size = lookup->size(),
                                                           .order = lookup->order(),
                                                           .segmentLength = lookup->segmentLength(),
                                                           .error = entry.structure.error};
        stats.setupSeconds += entry.buildSeconds;
        stats.setupReused = entry.reused;
        if (!entry.reused) setupSpent += entry.buildSeconds;
    }
    if (scene.brick) {  // a layer: no empty space skipped (the brick has no grid of its own), no bit changed
        dispatchVoxelType(scene.brick->voxels.type, [&](auto voxel) {
            const BrickGridSampler<decltype(voxel), Real> sampler(*scene.brick, scene.convention);
            renderWith<Real>(scene, sampler, nullptr, GridIndexing(scene.brick->dims(), scene.convention), camera, opt,
                             image, counters, nullptr, nullptr);
        });
        return;
    }
    if (!scene.volume && !scene.sparse) {
        renderWith<Real>(scene, LinearFieldSampler<Real>{}, nullptr, GridIndexing{}, camera, opt, image, counters,
                         log, lookup);
        return;
    }
    const OccupancyGrid* occupancy = nullptr;
    if (opt.skipEmptySpace && lookup && scene.volume && !(opt.simd && PacketScene::supports(scene, opt))) {
        const auto grid = cache.preintegrationGrid(scene.volume, scene.convention, scene.transferFunction,
                                                   lookup->segmentLength(), lookup->size(), lookup->order());
        occupancy = &grid.structure;  // the table's own empty space (dense volumes, the scalar path)
        stats.setupSeconds += grid.buildSeconds;
        stats.setupReused = stats.setupReused && grid.reused;
        if (!grid.reused) setupSpent += grid.buildSeconds;
        stats.emptyBrickFraction = occupancy->emptyFraction();
    }
    if (opt.skipEmptySpace && !lookup) {
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
        if (opt.skipEmptySpace) {  // the transfer function's empty space, or the table's own
            const auto entry =
                lookup ? cache.preintegrationStencils(scene.volume, scene.convention, scene.transferFunction,
                                                      lookup->segmentLength(), lookup->size(), lookup->order(),
                                                      rayOctants(camera))
                       : cache.stencilBricks(scene.volume, scene.convention, scene.transferFunction, rayOctants(camera));
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


Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats,
             OccupancyCache* cache) {
    validateRender(scene, camera, options);
    if (options.frames > 1)
        return averageFrames(options, stats, [&](const RenderOptions& frame, RenderStats* frameStats) {
            return render(scene, camera, frame, frameStats, cache);
        });
    const PixelRegion area = renderedRegion(options.region, camera);
    Image image = scene.brick ? brickLayerImage(area.width, area.height) : Image(area.width, area.height);
    RenderCounters counters;
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
    const MarchCounts& counts = counters.march;
    local.raysHit = counts.raysHit;
    local.samplesPlaced = counts.samplesPlaced;
    local.samplesEvaluated = counts.samplesEvaluated;
    local.raysTerminated = counts.raysTerminated;
    local.terminationLeftOut = counts.terminationLeftOut;
    if (local.preintegration && local.preintegration->order == 2) {
        // The lookups that added something per range of |delta|: (level k - 1, level k] of the checked deltas
        // ([0, 0] first), the last past them all.
        RenderStats::Preintegration& p = *local.preintegration;
        p.largestDelta = counts.largestDelta;
        const std::size_t levels = p.error.deltas.size();
        p.lookupsByDelta.assign(levels + 1, 0);
        for (std::size_t k = 0; k < levels; ++k)
            p.lookupsByDelta[k] = counts.lookupsBeyond[k] - counts.lookupsBeyond[k + 1];
        p.lookupsByDelta[levels] = counts.lookupsBeyond[levels];
    }
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
