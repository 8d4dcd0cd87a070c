#include "vri/render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <glm/vector_relational.hpp>
#include <glm/geometric.hpp>

#include "vri/error.h"
#include "vri/grid_sampler.h"
#include "vri/occupancy_grid.h"
#include "vri/progress.h"

namespace vri {

std::string_view precisionName(Precision p) { return p == Precision::Double ? "double" : "float"; }

Precision parsePrecision(std::string_view name, const std::string& what) {
    if (name == "double") return Precision::Double;
    if (name == "float") return Precision::Float;
    throw Error(what + ": unknown precision '" + std::string(name) + "' (expected double or float)");
}

Box Scene::box() const { return volume ? volumeBox(*volume, convention) : field->box; }

glm::dvec3 Scene::dims() const { return glm::dvec3(volume ? volume->dims : field->dims); }

namespace {

struct Counters {
    std::atomic<std::uint64_t> raysHit{0}, samplesPlaced{0}, samplesEvaluated{0};
};

// Maps texture coordinates to the occupancy grid's voxel index space: x = u * scale - offset.
struct IndexMap {
    glm::dvec3 scale, offset;
};

template <class Real, class Sampler>
void renderWith(const Scene& scene, const Sampler& sample, const OccupancyGrid* occupancy, const IndexMap& indexMap,
                const Camera& camera, const RenderOptions& opt, Image& image, Counters& counters) {
    using Vec = glm::vec<3, Real>;
    const Box box = scene.box();
    const Vec dims(scene.dims());
    const Vec eyeU(box.toTexture(camera.eye()));
    const Real rate = static_cast<Real>(opt.samplingRate);
    const Real ert = static_cast<Real>(opt.earlyTermination);
    const TransferFunction& tf = scene.transferFunction;
    const EmissionModel emission = tf.emission();
    const int tile = opt.tileSize;
    const int tilesX = (image.width + tile - 1) / tile, tilesY = (image.height + tile - 1) / tile;
    Progress progress("render", static_cast<std::uint64_t>(tilesX) * tilesY, opt.progress);

    tbb::parallel_for(tbb::blocked_range2d<int>(0, tilesY, 1, 0, tilesX, 1), [&](const auto& tiles) {
        std::uint64_t hit = 0, placed = 0, evaluated = 0;
        for (int ty = tiles.rows().begin(); ty < tiles.rows().end(); ++ty)
            for (int tx = tiles.cols().begin(); tx < tiles.cols().end(); ++tx) {
                for (int py = ty * tile; py < std::min((ty + 1) * tile, image.height); ++py)
                    for (int px = tx * tile; px < std::min((tx + 1) * tile, image.width); ++px) {
                        float* out = &image.at(px, py, 0);
                        const glm::dvec3 dir = camera.direction(px, py);
                        const auto segment = clipRay(camera.eye(), dir, box);
                        if (!segment) continue;
                        const double worldLength = segment->tFar - segment->tNear;
                        if (worldLength > 0) ++hit;
                        const Vec entry(box.toTexture(camera.eye() + segment->tNear * dir));
                        const Vec exit(box.toTexture(camera.eye() + segment->tFar * dir));
                        const SampleSchedule<Real> s = placeSamples<Real>(opt.placement, entry, exit, eyeU, dims, rate);
                        if (s.count == 0) continue;
                        const Vec du = (exit - entry) / s.tEnd;
                        const Real dx = s.tIncr * static_cast<Real>(worldLength / static_cast<double>(s.tEnd));
                        const OccupancyGrid::Ray indexRay(glm::dvec3(entry) * indexMap.scale - indexMap.offset,
                                                          glm::dvec3(du) * indexMap.scale);

                        RayAccumulator<Real> acc;
                        double knownOccupiedUntil = -std::numeric_limits<double>::infinity();
                        std::int64_t k = 0;
                        while (k < s.count) {
                            const Real t = s.t(k);
                            if (occupancy && static_cast<double>(t) >= knownOccupiedUntil) {
                                const auto brick = occupancy->visit(indexRay, static_cast<double>(t));
                                if (brick.empty) {
                                    // Jump to the first sample at or past the exit, counted on the
                                    // positions we evaluate; every sample skipped lies before the exit.
                                    if (!(brick.tExit < static_cast<double>(s.tEnd))) {
                                        k = s.count;  // the rest of the ray is empty
                                        break;
                                    }
                                    auto next = static_cast<std::int64_t>(std::ceil((brick.tExit - s.tStart) / s.tIncr));
                                    next = std::clamp<std::int64_t>(next, k + 1, s.count);
                                    while (next > k + 1 && static_cast<double>(s.t(next - 1)) >= brick.tExit) --next;
                                    k = next;
                                    continue;
                                }
                                knownOccupiedUntil = brick.tExit;
                            }
                            acc.add(opt.integrator, emission, tf(sample(entry + t * du)), dx);
                            ++evaluated;
                            ++k;
                            if (acc.transparency < ert) break;
                        }
                        placed += static_cast<std::uint64_t>(k);
                        out[0] = static_cast<float>(acc.r);
                        out[1] = static_cast<float>(acc.g);
                        out[2] = static_cast<float>(acc.b);
                        out[3] = static_cast<float>(acc.alpha());
                    }
                progress.advance(1);
            }
        counters.raysHit += hit;
        counters.samplesPlaced += placed;
        counters.samplesEvaluated += evaluated;
    });
}

template <class Real>
void renderScene(const Scene& scene, const Camera& camera, const RenderOptions& opt, Image& image,
                 Counters& counters, RenderStats& stats) {
    if (!scene.volume) {
        renderWith<Real>(scene, LinearFieldSampler<Real>{}, nullptr, IndexMap{}, camera, opt, image, counters);
        return;
    }
    const Volume& volume = *scene.volume;
    std::optional<OccupancyGrid> occupancy;
    if (opt.skipEmptySpace) {
        const auto start = std::chrono::steady_clock::now();
        occupancy.emplace(volume, scene.convention, scene.transferFunction);
        stats.setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats.emptyBrickFraction = occupancy->emptyFraction();
    }
    const bool cell = scene.convention == GridConvention::CellCentred;
    const glm::dvec3 n(volume.dims);
    const IndexMap indexMap{cell ? n : n - glm::dvec3(1.0), glm::dvec3(cell ? 0.5 : 0.0)};
    dispatchVoxelType(volume.type, [&](auto voxel) {
        const GridSampler<decltype(voxel), Real> sampler(volume, scene.convention);
        renderWith<Real>(scene, sampler, occupancy ? &*occupancy : nullptr, indexMap, camera, opt, image, counters);
    });
}

}  // namespace

Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats) {
    if (!(options.samplingRate > 0.0) || !std::isfinite(options.samplingRate))
        throw Error("sampling rate must be positive and finite (step h = 1 / rate > 0), got " +
                    std::to_string(options.samplingRate));
    if (options.tileSize < 1) throw Error("tile size must be at least 1");
    if (!scene.volume && !scene.field) throw Error("scene has neither a volume nor an analytic field");
    if (!(options.earlyTermination >= 0.0 && options.earlyTermination < 1.0))
        throw Error("early termination threshold must be in [0, 1), got " + std::to_string(options.earlyTermination));
    const glm::dvec3 dims = scene.dims();
    // The longest ray crosses |dims| voxels; keep its sample count well inside an int64 and a float.
    if (options.samplingRate * glm::length(dims) > 1e9)
        throw Error("sampling rate " + std::to_string(options.samplingRate) +
                    " per voxel would put more than 1e9 samples on a ray through this volume");
    if (scene.convention == GridConvention::NodeCentred && glm::any(glm::lessThan(dims, glm::dvec3(2.0))))
        throw Error("the node-centred convention needs at least 2 voxels along every axis (the box would be flat)");

    Image image(camera.width(), camera.height());
    Counters counters;
    RenderStats local;
    const auto start = std::chrono::steady_clock::now();
    if (options.precision == Precision::Double)
        renderScene<double>(scene, camera, options, image, counters, local);
    else
        renderScene<float>(scene, camera, options, image, counters, local);
    local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    local.rays = static_cast<std::uint64_t>(image.width) * image.height;
    local.raysHit = counters.raysHit;
    local.samplesPlaced = counters.samplesPlaced;
    local.samplesEvaluated = counters.samplesEvaluated;
    // The arena's concurrency ignores a tbb::global_control limit; the limit is what the workers get.
    local.threads = static_cast<int>(std::min<std::size_t>(
        tbb::this_task_arena::max_concurrency(),
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
    if (stats) *stats = local;
    return image;
}

}  // namespace vri
