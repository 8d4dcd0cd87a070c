#pragma once
// The packet engine: Riemann, composite and pre-integration in float on packets of rays, one ray per SIMD lane, with
// Google Highway dispatching at run time to the widest of SSE4, AVX2 and AVX-512 (AVX3) the CPU has.
// Each lane performs the scalar float path's operations in its order (the placement and empty-space
// jumps of fixed_step_ray.h, GridSampler's trilinear formula, TransferFunction's bracket and lerp,
// RayAccumulator's sums with the shared exponential of float_exp.h), so the image is bitwise equal to
// `--simd off` on every target. A packet holds a block of neighbouring pixels of a tile (their rays
// clipped and placed in vectors too); a lane whose ray has ended is masked until the packet's last ray
// ends. Empty space is skipped per sample, by the 4^3 brick of its trilinear stencil
// (StencilBricks, occupancy_grid.h): in each step a lane in an empty brick jumps to the samples
// leaving the cube of empty bricks around it, while the others evaluate their samples.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/box.h"
#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"
#include "libvri/core/early_termination.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/image.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/core/voxel_loads.h"

namespace vri {

struct MarchCounts {
    std::uint64_t raysHit = 0, samplesPlaced = 0, samplesEvaluated = 0;
    std::uint64_t raysTerminated = 0;  // rays ended early with samples left (early_termination.h)
    double terminationLeftOut = 0.0;   // the most those samples could have added to a channel
    // Second-order pre-integration, of the lookups whose value is not exactly 0 (those that add to a pixel:
    // a segment in the table's empty space is not looked up by every path): the largest |delta|, and how
    // many there were [0] and how many asked more than each of the table's checked deltas [k + 1]
    // (PreintegrationTable::checkedDeltas).
    double largestDelta = 0.0;
    std::array<std::uint64_t, PreintegrationTable::kMaxDeltaLevels + 1> lookupsBeyond{};

    // A ray ended early, leaving out samples that could have added at most `leftOut` to a channel.
    void terminated(double leftOut) {
        ++raysTerminated;
        terminationLeftOut = std::max(terminationLeftOut, leftOut);
    }
    // Another part's counts (a tile's, a thread's) added in.
    void merge(const MarchCounts& o) {
        raysHit += o.raysHit;
        samplesPlaced += o.samplesPlaced;
        samplesEvaluated += o.samplesEvaluated;
        raysTerminated += o.raysTerminated;
        terminationLeftOut = std::max(terminationLeftOut, o.terminationLeftOut);
        largestDelta = std::max(largestDelta, o.largestDelta);
        for (std::size_t level = 0; level < lookupsBeyond.size(); ++level)
            lookupsBeyond[level] += o.lookupsBeyond[level];
    }
};

// A scene as the packet engine reads it, built once per render.
struct PacketScene {
    // True when the packet engine can render this: float Riemann, composite or pre-integration of a volume
    // whose voxel and stencil-brick offsets fit 32-bit gathers, at least 2 voxels along x (the x neighbours are
    // gathered as a pair) and 4 bytes, and a transfer function of at most kMaxPoints points.
    static bool supports(const Scene& scene, const RenderOptions& options);
    static constexpr std::size_t kMaxPoints = 64;
    static constexpr std::size_t kMaxLanes = 16;  // floats in the widest vector (AVX-512)

    // stencils: null when empty space is not skipped; preintegration: the table of --method preintegrated.
    PacketScene(const Scene& scene, const Camera& camera, const StencilBricks* stencils, const RenderOptions& options,
                const PreintegrationTable* preintegration = nullptr);

    const Camera& camera;
    Box box;
    glm::vec3 eyeU, dims;
    GridIndexing indexMap;
    RenderOptions options;
    TerminationRule termination;
    EmissionModel emission;
    // The volume.
    const std::byte* voxels;
    VoxelType type;
    std::int32_t voxelBytes;
    GridSamplerLayout<float> layout;
    const PreintegrationTable* preintegration;  // null unless the method is preintegrated
    VoxelLoads voxelLoads;                      // how AVX2 reads an 8-bit volume's stencils and the distances
    // Per octant of ray directions and stencil brick, its distance to the nearest stencil brick ahead
    // that is not empty (StencilBricks::distances(), 0 when not empty), a byte each, padded for
    // 32-bit loads; null when skipping is off.
    const std::uint8_t* emptyDistance = nullptr;
    std::int32_t brickStride[3] = {0, 0, 0}, octantStride = 0;
    float jumpMargin = 0;  // voxels: far more than the rounding of a sample's position (see samplesInEmptyCube)
    // Whether voxelLoads decides any read on AVX2: an 8-bit volume's stencils, or the bricks' distances.
    bool readsByVoxelLoads() const { return type == VoxelType::UInt8 || emptyDistance != nullptr; }
    // The transfer function as TransferFunction::operator()<float> reads it: the points' s, and per
    // segment [s_i, s_i+1) its start, width and each channel's value at the start and slope (r, g, b,
    // tau), padded with copies of the last segment to a whole number of the widest vectors.
    std::vector<float> pointS;
    std::vector<float> innerS;  // pointS[1 .. n-2], padded with NaN to a multiple of 4
    std::size_t segments = 1;  // before the padding
    std::vector<float> segmentStart, segmentWidth, value[4], slope[4];
    float first[4], last[4];  // the channels at the first and the last point
    // Below this s (compared in float, as the bracket is) a sample adds exactly nothing: the transfer
    // function is invisible from below its first point up to there (TransferFunction::isInvisible). -inf
    // when its first point is visible, +inf when all are.
    float invisibleBelow;
    float maxTau;  // the largest extinction of a point: a sample's, a lerp between two, is at most an ulp more
};

// Renders the pixels x0 <= x < x1, y0 <= y < y1 of the camera's image into `image`, which holds the
// options' region (renderedRegion()), adding to `counts`.
void marchPackets(const PacketScene& scene, int x0, int y0, int x1, int y1, Image& image, MarchCounts& counts);

// The Highway target marchPackets() runs on ("AVX2", "AVX3", ...).
std::string packetTargetName();

}  // namespace vri
