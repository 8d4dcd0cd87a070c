#include "libvri/core/exact_reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "libvri/core/exact_empty_space.h"
#include "libvri/core/exact_piece_batch.h"
#include "libvri/core/exact_ray.h"
#include "libvri/core/occupancy_cache.h"
#include "libvri/core/simd_target.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/progress.h"

namespace vri {

namespace {

struct PieceCounts {
    std::uint64_t pieces = 0, visible = 0;
};

// One thread's walk in progress: the pieces walked but not yet given to the ray, in walk order. Each
// visible one waits in `batch` for its cubic (exact_piece_batch.h); an invisible one only for the ray's
// done() test, which its end may answer (g = C: the length left shrinks).
struct WalkQueue {
    static constexpr int kCapacity = 4 * PieceBatch::kCapacity;
    PieceBatch batch;
    int visible = 0, entries = 0;
    double phiB[kCapacity];
    int lane[kCapacity];  // into batch, -1 for an invisible piece
};

// The pieces of a ray through a volume on which the trilinear interpolant is one cubic: the ray's
// voxel-index coordinates x(phi) = entry + phi (exit - entry), phi in [0, 1], split wherever an axis
// crosses an integer in [0, n - 1]. Between those planes the cell and the clamping of every axis are
// fixed, so each weight is linear in phi (or constant where clamped) and the interpolant a cubic.
template <class T>
class GridWalker {
public:
    // `empty` tells which cells are invisible; with `skipEmpty` the walk jumps over its empty regions
    // and blocks.
    GridWalker(const Volume& volume, GridConvention convention, const ExactEmptySpace& empty, bool skipEmpty)
        : data_(volume.data<T>()), empty_(empty), skipEmpty_(skipEmpty), blocks_(empty.blocks()) {
        const bool cell = convention == GridConvention::CellCentred;
        for (int a = 0; a < 3; ++a) {
            n_[a] = volume.dims[a];
            scale_[a] = cell ? n_[a] : n_[a] - 1.0;  // as GridSampler and render()'s index map
            offset_[a] = cell ? 0.5 : 0.0;
            maxCoord_[a] = n_[a] - 1.0;
            maxBase_[a] = std::max(n_[a] - 2, 0);
        }
        stride_[0] = n_[0] > 1 ? 1 : 0;  // a single layer: both taps read it
        stride_[1] = n_[1] > 1 ? std::int64_t(n_[0]) : 0;
        stride_[2] = n_[2] > 1 ? std::int64_t(n_[0]) * n_[1] : 0;
        for (int k = 0; k < 8; ++k)
            corner_[k] = (k & 1) * stride_[0] + (k >> 1 & 1) * stride_[1] + (k >> 2) * stride_[2];
        const ValueRange r = volume.normalisationRange();
        lo_ = r.lo;
        invRange_ = r.hi > r.lo ? 1.0 / (r.hi - r.lo) : 0.0;
    }

    // Integrates the segment from texture coordinate uEntry to uExit, `length` world units long,
    // into `ray` until it is done(); returns the length left out.
    double walk(const glm::dvec3& uEntry, const glm::dvec3& uExit, double length, ExactRay& ray,
                PieceCounts& counts, WalkQueue& queue) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        const glm::dvec3 entry = uEntry * scale_ - offset_;
        const glm::dvec3 delta = (uExit * scale_ - offset_) - entry;
        const glm::dvec3 exit = entry + delta;
        int next[3], step[3], cell[3];
        double phi[3];
        auto planeAt = [&](int a, int plane) { return (plane - entry[a]) / delta[a]; };
        // The parameter where axis a crosses the integer next[a], or inf when no plane is left before the exit.
        auto crossing = [&](int a) {
            const bool left = step[a] > 0 ? next[a] <= n_[a] - 1 && next[a] < exit[a]
                                          : step[a] < 0 && next[a] >= 0 && next[a] > exit[a];
            return left ? planeAt(a, next[a]) : inf;
        };
        // The base corner of the cell between the planes the axis last crossed and next[a] (clamped like
        // cellOf; an axis the ray does not move along keeps the entry's).
        auto cellBetween = [&](int a) {
            return std::clamp(step[a] > 0 ? next[a] - 1 : next[a], 0, maxBase_[a]);
        };
        PieceFrame frame;
        for (int a = 0; a < 3; ++a) {
            frame.entry[a] = entry[a];
            frame.delta[a] = delta[a];
            frame.maxCoord[a] = maxCoord_[a];
            frame.varies[a] = n_[a] > 1;
        }
        frame.lo = lo_;
        frame.invRange = invRange_;
        queue.visible = queue.entries = 0;
        // The queued pieces to the ray, in order, while it is not done: the length it left out, or -1.
        auto drain = [&]() -> double {
            formPieceCubics(queue.batch, queue.visible, frame);
            const PieceBatch& b = queue.batch;
            for (int e = 0; e < queue.entries; ++e) {
                ++counts.pieces;
                if (const int j = queue.lane[e]; j >= 0) {
                    ++counts.visible;
                    const ExactRay::PieceCell cell{b, j, lo_, invRange_};
                    ray.addPiece((b.phiB[j] - b.phiA[j]) * length, Cubic{{b.c[0][j], b.c[1][j], b.c[2][j], b.c[3][j]}},
                                 b.sScale[j], b.exact[j] != 0.0, &cell);
                }
                if (ray.done((1.0 - queue.phiB[e]) * length)) return (1.0 - queue.phiB[e]) * length;
            }
            queue.visible = queue.entries = 0;
            return -1.0;
        };
        for (int a = 0; a < 3; ++a) {
            step[a] = delta[a] > 0 ? 1 : delta[a] < 0 ? -1 : 0;
            next[a] = step[a] > 0 ? std::max(static_cast<int>(std::floor(entry[a])) + 1, 0)
                                  : std::min(static_cast<int>(std::ceil(entry[a])) - 1, n_[a] - 1);
            phi[a] = crossing(a);
        }
        cellOf(entry, delta, 0.0, cell);
        for (int a = 0; a < 3; ++a)
            if (step[a] != 0) cell[a] = cellBetween(a);
        // Puts every axis where the plane-by-plane walk would be once it has passed the event at phiJump:
        // on the first plane crossed after it. Crossings grow with the plane index, so a short search
        // from the plane under the jump's point finds it.
        auto jumpTo = [&](double phiJump) {
            for (int a = 0; a < 3; ++a) {
                if (step[a] == 0) continue;
                const double x = entry[a] + phiJump * delta[a];
                int plane = step[a] > 0 ? std::max(static_cast<int>(std::floor(x)), next[a])
                                        : std::min(static_cast<int>(std::ceil(x)), next[a]);
                while (planeAt(a, plane) <= phiJump) plane += step[a];
                while (plane != next[a] && planeAt(a, plane - step[a]) > phiJump) plane -= step[a];
                next[a] = plane;
                phi[a] = crossing(a);
                cell[a] = cellBetween(a);
            }
        };
        double phiA = 0.0;
        for (;;) {
            const double phiB = std::min({phi[0], phi[1], phi[2], 1.0});
            if (phiB > phiA) {
                if (skipEmpty_ && emptyBlockOfCell(cell)) {
                    // The piece's block is empty: every piece up to the end of the run of empty blocks
                    // lies in cells whose corners the blocks' emptiness covers, each invisible.
                    const double until = emptyFrom(entry, delta, 0.5 * (phiA + phiB));
                    if (until >= 1.0) return std::max(drain(), 0.0);
                    if (until > phiA) {  // (a rounding error cannot stop the walk)
                        jumpTo(until);
                        phiA = until;
                        continue;
                    }
                }
                queuePiece(cell, phiA, phiB, queue);
                if (queue.visible == PieceBatch::kCapacity || queue.entries == WalkQueue::kCapacity)
                    if (const double left = drain(); left >= 0.0) return left;
            }
            if (phiB >= 1.0) return std::max(drain(), 0.0);
            for (int a = 0; a < 3; ++a)
                if (phi[a] == phiB) {
                    next[a] += step[a];
                    phi[a] = crossing(a);
                    cell[a] = cellBetween(a);
                }
            phiA = phiB;
        }
    }

private:
    static constexpr int kBlockShift = ExactEmptySpace::kBlockShift;
    static constexpr int kBlock = 1 << kBlockShift;
    static constexpr int kRegion = 1 << ExactEmptySpace::kRegionShift;  // blocks per region edge

    // From the empty block that holds the ray's point at phi, the blocks the ray passes while they are
    // empty: where the first non-empty one begins (1 when none is left). A block DDA, one division per
    // block, and where a whole region is empty one step to its far side. Every face is a plane of
    // integer index, crossed at the parameter the cell walk computes for it, so a jump lands exactly on
    // a cell face.
    double emptyFrom(const glm::dvec3& entry, const glm::dvec3& delta, double phi) const {
        constexpr double inf = std::numeric_limits<double>::infinity();
        int m[3];
        double exitAt[3];
        auto planeAt = [&](int a, int plane) { return (plane - entry[a]) / delta[a]; };
        // Where the ray leaves the block m[a] of axis a (the first and last own the clamped outside).
        auto exitOf = [&](int a) {
            if (delta[a] > 0 && m[a] + 1 < blocks_[a]) return planeAt(a, (m[a] + 1) * kBlock);
            if (delta[a] < 0 && m[a] > 0) return planeAt(a, m[a] * kBlock);
            return inf;
        };
        auto firstOfAxis = [](const double at[3]) {
            return at[0] <= at[1] ? (at[0] <= at[2] ? 0 : 2) : (at[1] <= at[2] ? 1 : 2);
        };
        for (int a = 0; a < 3; ++a) {
            const double x = std::clamp(entry[a] + phi * delta[a], 0.0, maxCoord_[a]);
            m[a] = std::min(static_cast<int>(x) >> kBlockShift, blocks_[a] - 1);
            exitAt[a] = exitOf(a);
        }
        for (;;) {
            if (empty_.emptyRegionOf(m)) {
                // To the region's far side: the axis that leaves it first steps into the next region,
                // the others to the block whose faces the ray crosses after that point, searched by the
                // same plane parameters as the block DDA.
                double regionExit[3];
                for (int a = 0; a < 3; ++a) {
                    const int first = m[a] & ~(kRegion - 1);
                    regionExit[a] = delta[a] > 0 && first + kRegion < blocks_[a] ? planeAt(a, (first + kRegion) * kBlock)
                                    : delta[a] < 0 && first > 0                ? planeAt(a, first * kBlock)
                                                                               : inf;
                }
                const int a = firstOfAxis(regionExit);
                const double until = regionExit[a];
                if (!(until < 1.0)) return 1.0;
                m[a] = delta[a] > 0 ? (m[a] | (kRegion - 1)) + 1 : (m[a] & ~(kRegion - 1)) - 1;
                for (int b = 0; b < 3; ++b) {
                    if (b != a && delta[b] != 0) {
                        while ((exitAt[b] = exitOf(b)) <= until) m[b] += delta[b] > 0 ? 1 : -1;
                    }
                    exitAt[b] = exitOf(b);
                }
                if (!empty_.emptyBlock(m)) return until;
                continue;
            }
            const int a = firstOfAxis(exitAt);
            const double until = exitAt[a];
            if (!(until < 1.0)) return 1.0;
            m[a] += delta[a] > 0 ? 1 : -1;
            if (!empty_.emptyBlock(m)) return until;
            exitAt[a] = exitOf(a);
        }
    }

    bool emptyBlockOfCell(const int cell[3]) const {
        const int m[3] = {cell[0] >> kBlockShift, cell[1] >> kBlockShift, cell[2] >> kBlockShift};
        return empty_.emptyBlock(m);
    }

    // The base corner of the cell that holds the ray's point at phi (clamped where the axis is).
    void cellOf(const glm::dvec3& entry, const glm::dvec3& delta, double phi, int cell[3]) const {
        for (int a = 0; a < 3; ++a)
            cell[a] = std::min(static_cast<int>(std::clamp(entry[a] + phi * delta[a], 0.0, maxCoord_[a])), maxBase_[a]);
    }

    // The piece between phiA and phiB, in the cell from its middle, onto the queue: with its corners
    // when it is visible, for formPieceCubics (the weights at its ends, clamped where the axis is, and
    // its cubic); an invisible piece adds nothing to the ray and needs neither.
    void queuePiece(const int cell[3], double phiA, double phiB, WalkQueue& queue) const {
        const T* p = data_ + cell[0] * stride_[0] + cell[1] * stride_[1] + cell[2] * stride_[2];
        T corner[8];
        for (int k = 0; k < 8; ++k) corner[k] = p[corner_[k]];
        // The interpolant is a convex combination of the corners: their range bounds it. (A tree of
        // min and max, without the branches of std::minmax_element, which mispredict on noisy data;
        // the rest only once the cell is visible, as 4 in 10 of the cells walked are not.)
        const double vMin = static_cast<double>(
            std::min(std::min(std::min(corner[0], corner[1]), std::min(corner[2], corner[3])),
                     std::min(std::min(corner[4], corner[5]), std::min(corner[6], corner[7]))));
        const double vMax = static_cast<double>(
            std::max(std::max(std::max(corner[0], corner[1]), std::max(corner[2], corner[3])),
                     std::max(std::max(corner[4], corner[5]), std::max(corner[6], corner[7]))));
        const int e = queue.entries++;
        queue.phiB[e] = phiB;
        if (empty_.invisible(vMin, vMax)) {
            queue.lane[e] = -1;
            return;
        }
        const int j = queue.visible++;
        queue.lane[e] = j;
        PieceBatch& b = queue.batch;
        for (int k = 0; k < 8; ++k) b.corner[k][j] = static_cast<double>(corner[k]);
        for (int a = 0; a < 3; ++a) b.cell[a][j] = cell[a];
        b.phiA[j] = phiA;
        b.phiB[j] = phiB;
        b.magnitude[j] = std::max(std::abs(vMin), std::abs(vMax));
    }

    const T* data_;
    const ExactEmptySpace& empty_;
    bool skipEmpty_;
    glm::ivec3 blocks_;
    int n_[3];
    std::int64_t stride_[3];
    std::int64_t corner_[8];  // offset of corner (dx, dy, dz) = k & 1, k >> 1 & 1, k >> 2 from a cell's base
    glm::dvec3 scale_, offset_;
    double maxCoord_[3];
    int maxBase_[3];
    double lo_, invRange_;
};

struct Counters {
    std::atomic<std::uint64_t> raysHit{0}, pieces{0}, visible{0}, subPieces{0}, intervals{0}, nodes{0}, opaque{0},
        wholeWindow{0};
};

// Calls walk(uEntry, uExit, length, ray, counts, queue) -> length left out, for every pixel's ray that
// crosses the box, in parallel over tiles, and stores its result.
template <class Walk>
void traceRays(const Scene& scene, const Camera& camera, const ExactReferenceOptions& opt, const Walk& walk,
               ExactReference& out, Counters& counters) {
    const Box box = scene.box();
    const PixelRegion area = renderedRegion(opt.region, camera);  // `out` holds these pixels
    const int tile = opt.tileSize;
    const int tilesX = (area.width + tile - 1) / tile, tilesY = (area.height + tile - 1) / tile;
    Progress progress("reference", static_cast<std::uint64_t>(tilesX) * tilesY, opt.progress);
    tbb::parallel_for(tbb::blocked_range2d<int>(0, tilesY, 1, 0, tilesX, 1), [&](const auto& tiles) {
        ExactRay ray(scene.transferFunction, opt.tolerance);
        PieceCounts counts;
        WalkQueue queue;
        std::uint64_t hit = 0, opaque = 0, wholeWindow = 0;
        for (int ty = tiles.rows().begin(); ty < tiles.rows().end(); ++ty)
            for (int tx = tiles.cols().begin(); tx < tiles.cols().end(); ++tx) {
                for (int iy = ty * tile; iy < std::min((ty + 1) * tile, area.height); ++iy)
                    for (int ix = tx * tile; ix < std::min((tx + 1) * tile, area.width); ++ix) {
                        const glm::dvec3 dir = camera.direction(area.x + ix, area.y + iy);
                        const auto segment = clipRay(camera.eye(), dir, box);
                        if (!segment || !(segment->tFar > segment->tNear)) continue;  // nothing to integrate
                        ++hit;
                        const glm::dvec3 entry = box.toTexture(camera.eye() + segment->tNear * dir);
                        const glm::dvec3 exit = box.toTexture(camera.eye() + segment->tFar * dir);
                        ray.begin();
                        const double left = walk(entry, exit, segment->tFar - segment->tNear, ray, counts, queue);
                        if (left > 0.0) ++opaque;
                        wholeWindow += ray.wholeSubPieceWindow();
                        const std::size_t at = (static_cast<std::size_t>(iy) * out.width + ix) * 4;
                        ray.finish(left, &out.values[at], &out.bounds[at]);
                    }
                progress.advance(1);
            }
        counters.raysHit += hit;
        counters.opaque += opaque;
        counters.wholeWindow += wholeWindow;
        counters.pieces += counts.pieces;
        counters.visible += counts.visible;
        counters.subPieces += ray.subPieces;
        counters.intervals += ray.quadratureIntervals;
        counters.nodes += ray.quadratureNodes;
    });
}

// A bound on |float(value) - exact| from the double's bound: plus the rounding |float(v) - v| (exact in
// double: the two are within a factor 2, Sterbenz), the sum rounded up to the next float.
float storedValueBound(double value, double bound) {
    const double total = bound + std::abs(static_cast<double>(static_cast<float>(value)) - value);
    const float f = static_cast<float>(total);
    return static_cast<double>(f) >= total ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

Image toImage(const std::vector<double>& v, int width, int height) {
    Image image(width, height);
    std::transform(v.begin(), v.end(), image.pixels.begin(), [](double x) { return static_cast<float>(x); });
    return image;
}

}  // namespace

Image ExactReference::image() const { return toImage(values, width, height); }

Image ExactReference::boundImage() const {
    Image image(width, height);
    for (std::size_t i = 0; i < values.size(); ++i)
        image.pixels[i] = storedValueBound(values[i], bounds[i]);
    return image;
}

ExactReference renderExactReference(const Scene& scene, const Camera& camera, const ExactReferenceOptions& options,
                                    OccupancyCache* cache) {
    ExactReference out;
    renderExactReference(scene, camera, options, cache, out);
    return out;
}

void renderExactReference(const Scene& scene, const Camera& camera, const ExactReferenceOptions& options,
                          OccupancyCache* cache, ExactReference& out) {
    if (!scene.volume && !scene.field) throw Error("scene has neither a volume nor an analytic field");
    if (!(options.tolerance > 0.0)) throw Error("exact method: the tolerance must be positive, got " + exactNumber(options.tolerance));
    if (options.tileSize < 1) throw Error("tile size must be at least 1");
    if (scene.volume && scene.convention == GridConvention::NodeCentred &&
        glm::any(glm::lessThan(scene.volume->dims, glm::ivec3(2))))
        throw Error("the node-centred convention needs at least 2 voxels along every axis (the box would be flat)");

    // Each piece's optical depth must be a finite double: refuse extinctions near the top of its range.
    const double largestTau = scene.transferFunction.largest().tau;
    const Box box = scene.box();
    const double diagonal = glm::length(box.size());
    if (!std::isfinite(64.0 * largestTau * diagonal))
        throw Error("transfer function: extinction " + exactNumber(largestTau) + " per unit length over a box " +
                    exactNumber(diagonal) + " long: the optical depth overflows double");

    out.stats = {};
    if (options.tolerance >= ExactRay::kGaussTolerance) {
        useSimdTarget(options.simdTarget);  // before the threads start (simd_target.h)
        out.stats.simdTarget = gaussBatchTarget();
    }
    const PixelRegion area = renderedRegion(options.region, camera);  // checked before anything is allocated
    out.width = area.width;
    out.height = area.height;
    // Values and bounds in double: twice the image's bytes each, checked before they are allocated.
    const std::size_t n = checkedBytes("the exact reference of a " + std::to_string(out.width) + "x" +
                                           std::to_string(out.height) + " image",
                                       {std::uint64_t(out.width), std::uint64_t(out.height), 4, 2 * sizeof(double)}) /
                          (2 * sizeof(double));
    out.values.assign(n, 0.0);
    out.bounds.assign(n, 0.0);
    Counters counters;
    const auto start = std::chrono::steady_clock::now();
    if (scene.volume) {
        const Volume& volume = *scene.volume;
        OccupancyCache once;  // without a cache, this frame builds its own empty space
        const auto empty = (cache ? *cache : once).exactEmptySpace(scene.volume, scene.convention, scene.transferFunction);
        out.stats.setupSeconds = empty.buildSeconds;
        out.stats.setupReused = empty.reused;
        dispatchVoxelType(volume.type, [&](auto voxel) {
            const GridWalker<decltype(voxel)> walker(volume, scene.convention, empty.structure, options.skipEmptySpace);
            traceRays(scene, camera, options, [&](const glm::dvec3& a, const glm::dvec3& b, double length, ExactRay& ray,
                                                  PieceCounts& counts, WalkQueue& queue) {
                return walker.walk(a, b, length, ray, counts, queue);
            },
                      out, counters);
        });
    } else {
        // The analytic field s = u.x is linear along the ray: one piece, split only at TF points.
        traceRays(scene, camera, options, [](const glm::dvec3& a, const glm::dvec3& b, double length, ExactRay& ray,
                                             PieceCounts& counts, WalkQueue&) {
            ++counts.pieces;
            ++counts.visible;
            const Cubic s{{a.x, b.x - a.x, 0.0, 0.0}};
            ray.addPiece(length, s, std::abs(a.x) + 2.0 * std::abs(b.x - a.x), false);
            return 0.0;
        }, out, counters);
    }

    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(out.values[i]) || !std::isfinite(out.bounds[i]))
            throw Error("exact method: pixel " + std::to_string(area.x + i / 4 % out.width) + "," +
                        std::to_string(area.y + i / 4 / out.width) + " has a " +
                        (std::isfinite(out.values[i]) ? "non-finite error bound" : "non-finite value") +
                        " (an extinction or transfer-function slope too large for double)");

    ExactReferenceStats& st = out.stats;
    // The frame's own work: what this call spent building the empty space is setup, reported on its own.
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                 (st.setupReused ? 0.0 : st.setupSeconds);
    st.rays = static_cast<std::uint64_t>(out.width) * out.height;
    st.raysHit = counters.raysHit;
    st.pieces = counters.pieces;
    st.piecesVisible = counters.visible;
    st.subPieces = counters.subPieces;
    st.quadratureIntervals = counters.intervals;
    st.quadratureNodes = counters.nodes;
    st.raysOpaque = counters.opaque;
    st.raysWholeSubPieceWindow = counters.wholeWindow;
    // The arena's concurrency ignores a tbb::global_control limit; the limit is what the workers get.
    st.threads = static_cast<int>(std::min<std::size_t>(
        tbb::this_task_arena::max_concurrency(),
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
    for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (std::size_t i = c; i < n; i += 4) {
            st.maxBound[c] = std::max(st.maxBound[c], out.bounds[i]);
            sum += out.bounds[i];
            const double rounding = std::abs(static_cast<double>(static_cast<float>(out.values[i])) - out.values[i]);
            st.maxFloatRounding[c] = std::max(st.maxFloatRounding[c], rounding);
            st.maxStoredBound[c] = std::max(st.maxStoredBound[c], static_cast<double>(storedValueBound(out.values[i], out.bounds[i])));
        }
        st.meanBound[c] = sum / static_cast<double>(st.rays);
    }
}

}  // namespace vri
