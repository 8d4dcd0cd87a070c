#pragma once
// The render contract: what is rendered (Scene), how (RenderOptions) and what a render reports
// (RenderStats), with the checks every backend applies before it renders. The CPU raycaster
// (cpu_renderer.h), the packet engine, the exact method and the Vulkan backend all render against it.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/core/adaptive_simpson.h"
#include "libvri/core/analytic_field.h"
#include "libvri/core/camera.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/image.h"
#include "libvri/core/integrator.h"
#include "libvri/core/nonfinite_pixels.h"
#include "libvri/core/placement.h"
#include "libvri/core/simpson_range.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/core/transfer_function.h"
#include "libvri/core/volume.h"

namespace vri {

class SparseVolume;  // sparse_volume.h
struct BrickVolume;  // brick_volume.h

enum class Precision { Double, Float };
std::string_view precisionName(Precision p);  // "double", "float"
Precision parsePrecision(std::string_view name, const std::string& what);
struct RenderOptions;
// --simd: "on" (the best SIMD target, or VRI_SIMD_TARGET's), "off" (the scalar path) or a target's name
// (simd_target.h); sets options.simd and options.simdTarget.
void parseSimd(std::string_view name, const std::string& what, RenderOptions& options);
// Whether the packet engine (simd_march.h) runs this method: float Riemann, composite or pre-integration.
bool packetMethod(const RenderOptions& options);
// --early-termination: a transparency in [0, 1) below which rays stop (0: off), `auto` (rays stop once
// what is left can change no channel by more than kAutoTerminationBound) or `auto:BOUND` with a bound in
// (0, 1); sets options.earlyTermination or options.terminationBound.
void parseEarlyTermination(const std::string& text, const std::string& what, RenderOptions& options);
constexpr double kAutoTerminationBound = 1e-4;  // a tenth of the finest error threshold the tables count

// What is rendered: a volume under a grid convention, or an analytic field evaluated exactly.
struct Scene {
    std::shared_ptr<const Volume> volume;  // set for volume scenes
    std::optional<LinearField> field;      // set for analytic scenes
    GridConvention convention = GridConvention::CellCentred;
    TransferFunction transferFunction;
    // Set instead of `volume` for a volume kept sparse (sparse_volume.h). The CPU renderer's scalar path
    // renders it, bitwise as the dense volume (the packet engine, the exact method and Vulkan read dense
    // volumes only: the SIMD option falls back to the scalar path, the others refuse it).
    std::shared_ptr<const SparseVolume> sparse = nullptr;
    // Set instead of `volume` for one brick of a dense volume (brick_volume.h): the box, the rays and the
    // samples are the whole volume's, and the CPU's scalar path sums the samples the brick owns into a
    // layer (brick_layers.h), in double, for Riemann and composite. Nothing else renders a brick.
    std::shared_ptr<const BrickVolume> brick = nullptr;

    Box box() const;
    glm::dvec3 dims() const;  // the grid resolution paper A's placements use
};

struct RenderOptions {
    Integrator integrator = Integrator::Riemann;
    Placement placement = Placement::EntryAlign;
    double samplingRate = 2.0;  // samples per voxel along the ray (paper A); the step is h = 1 / rate voxels
    // Coupled and decoupled: paper B's parameters (the coupling follows the integrator). Uniform
    // Simpson takes its step from samplingRate and ignores these.
    AdaptiveParameters adaptive;
    std::optional<glm::ivec2> logPixel;  // record every try of the adaptive methods along this pixel's ray
    Precision precision = Precision::Double;
    // Stop a ray once its transparency falls below this; 0 (the default) integrates every ray to
    // its exit, as accuracy studies need.
    double earlyTermination = 0.0;
    // Or stop a ray once the samples left could change no channel by more than this (0: off; see
    // libvri/core/early_termination.h). The stats give the most any ended ray left out.
    double terminationBound = 0.0;
    // Pre-integrated classification (--method preintegrated): the table's entries per axis and its order
    // (1: the scalar linear along a segment; 2: quadratic through the midpoint too).
    int preintegrationSize = PreintegrationTable::kDefaultSize;
    int preintegrationOrder = 1;
    // Jittered sampling (jitter.h) of the placed fixed-step methods: frame f of `frames` moves each ray's
    // first sample by the hash of its pixel and seed + f, and the image is the frames' mean.
    bool jitter = false;
    std::uint32_t seed = 0;
    int frames = 1;
    bool skipEmptySpace = true;  // never changes the image (see occupancy_grid.h)
    // Float Riemann and composite of a volume on packets of rays, one per SIMD lane; bitwise equal to
    // the scalar float path (false), which stays the reference.
    bool simd = true;
    // The Highway target the packets run on (simd_target.h): empty for VRI_SIMD_TARGET's, else the best.
    std::string simdTarget;
    int tileSize = 16;
    // Render only these pixels of the camera's image (the image returned is the region's size): each is
    // computed as in the whole image, bit for bit, since every pixel is computed on its own.
    std::optional<PixelRegion> region;
    bool progress = false;  // report progress on stderr
};

struct RenderStats {
    std::uint64_t rays = 0;              // pixels (of the region, when RenderOptions::region is set)
    std::uint64_t raysHit = 0;           // rays whose segment in the box has positive length
    std::uint64_t samplesPlaced = 0;     // samples the placement puts on the rays (up to early termination)
    std::uint64_t samplesEvaluated = 0;  // of those, the ones not skipped as empty space
    double seconds = 0.0;                // wall time of the frame's own work (excludes loading and setup)
    // CPU: building the empty-space grid this frame used, in this call or the one that built it
    // (occupancy_cache.h). Vulkan: what this call spent on setup (grid, upload, pipelines).
    double setupSeconds = 0.0;
    bool setupReused = false;  // the grid came from an earlier frame of the same scene
    int threads = 0;
    double emptyBrickFraction = 0.0;
    // Early termination: the rays ended before their last sample, and the most the samples they left
    // out could have added to any channel (max over those rays; 0 when none ended early).
    std::uint64_t raysTerminated = 0;
    double terminationLeftOut = 0.0;
    std::optional<AdaptiveCounts> adaptive;  // Simpson methods: tries, failures, steps and points of all rays
    // Simpson methods on the CPU: the largest tau h of a step and the rays beyond simpson_range.h's limit.
    std::optional<SimpsonRange> simpsonRange;
    // Pre-integration: the table's segment length (world units) and its own error against direct
    // evaluation (PreintegrationTable::check); building and checking it is setup (setupSeconds).
    struct Preintegration {
        int size = 0, order = 0;
        double segmentLength = 0.0;
        PreintegrationError error;
        // Order 2 on the CPU: the largest |delta| the render's lookups asked (scalar units); the Vulkan
        // backend does not count it.
        std::optional<double> largestDelta;
        std::vector<std::uint64_t> lookupsByDelta;  // the lookups per range of |delta| (render_json.cpp)
    };
    std::optional<Preintegration> preintegration;
    std::vector<AdaptiveTry> rayLog;  // the tries along RenderOptions::logPixel's ray
    std::string backend = "cpu";      // "cpu" or "vulkan" (vulkan_renderer.h)
    std::string device;               // the Vulkan device's name; empty on the CPU
    std::string interpolation;        // the Vulkan backend's: "shader" or "sampler"; empty on the CPU
    std::string simdTarget;  // the packet engine's Highway target ("AVX2", ...); empty when the scalar path ran
    // On AVX2, how the packets read an 8-bit volume's stencils and the bricks' distances (voxel_loads.h):
    // "gather" or "scalar"; empty where neither is read (or another target ran).
    std::string voxelLoads;
    NonFinitePixels nonfinite;  // the image's NaN and infinite pixels, found after the render
};

// The pixels a render computes: `region` when given, else the camera's whole image. Throws vri::Error on a
// region that is not inside the image.
PixelRegion renderedRegion(const std::optional<PixelRegion>& region, const Camera& camera);

// Throws vri::Error "--brick: ..." unless a brick can render with these options (Scene::brick).
void requireBrickable(const RenderOptions& options);
// Throws vri::Error on options render() cannot honour (see render()); shared with the Vulkan backend.
void validateRender(const Scene& scene, const Camera& camera, const RenderOptions& options);
// The parameters the Simpson methods run with: uniform Simpson's h0 = h_min = h_max = 1 / samplingRate,
// coupled; coupled and decoupled take options.adaptive with the coupling of their name.
AdaptiveParameters simpsonParameters(const RenderOptions& options);

// The length in world units of the segments a pre-integration table is built for: the step h along the
// box's x axis as the placement counts voxels (every segment of Entry or Eye Align on a volume of equal
// spacings; other segments scale it, RayAccumulator::addSegment).
double preintegrationSegmentLength(const Scene& scene, const RenderOptions& options);

}  // namespace vri
