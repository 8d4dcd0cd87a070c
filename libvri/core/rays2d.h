#pragma once
// Paper A's 2D analytic study (Sec. V-A, Figs. 1-3): a fan of rays from an eye through a rotated
// square holding f(x, y) = (x + 1.5) / 3 on a 5x5 grid, with g(s) = s, tau(s) = s / 2 and I0 = 0.
// A 2D scene stays 2D: the square is a 5x5x1 grid and every point has z = 0.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "libvri/core/analytic_field.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/placement.h"
#include "libvri/core/volume.h"

namespace vri {

// The study's limits: rays in the fan, and samples of all its discrete sums together (or of the
// diagram's rays), so that a mistyped --rays or --rates is refused instead of running for hours.
inline constexpr std::uint64_t kMaxRays2D = 1000000;
inline constexpr double kMaxFanSamples = 1e9;
inline constexpr double kMaxDiagramSamples = 1e6;
// Points of the field image (2048 x 2048), a CSV row each.
inline constexpr std::uint64_t kMaxFieldPoints = std::uint64_t(1) << 22;

struct Study2D {
    glm::dvec2 eye{-9.0, 0.0};
    double rotationRadians = 3.14159265358979323846 / 7.0;  // of the square about the origin
    double side = 3.0;                                        // the square is centred at the origin
    int gridSize = 5;                                         // f is discretised on gridSize^2 voxels
    GridConvention convention = GridConvention::NodeCentred;
    int rays = 120;
    double fovDegrees = 30.0;
    // Ray i leaves the eye at angle -fov/2 + (i + 1/2) fov / rays from the +x axis: equal angular
    // spacing with the rays at the centres of `rays` equal sectors, like pixel centres.
    double rayAngleDegrees(int i) const;
    glm::dvec2 rayDirection(int i) const;  // unit, world frame

    // The square's own frame (axis-aligned, f varies with its x) and the world frame it is rotated into.
    glm::dvec2 toWorld(const glm::dvec2& local) const;
    glm::dvec2 toLocal(const glm::dvec2& world) const;
};

struct Ray2D {
    int index;
    double angleDegrees;
    double length;         // D: length of the ray inside the square, world units (0 for a miss)
    double opticalDepth;   // F(D) / 2 = ∫ tau along the ray, exact
    double closedForm;     // I = ∫ g exp(-∫ tau) = 2 (1 - exp(-F(D) / 2)), exact (g = 2 tau)
};

struct DiscreteRay {
    double intensity;  // paper A eq. (6)
    std::int64_t samples;
    double step;       // world units
};

// Where a placement puts the samples of one ray, in the world frame, for diagrams.
struct RaySamples {
    glm::dvec2 entry{0.0}, direction{0.0};  // direction: unit
    double length = 0.0;                    // D, world units
    double step = 0.0;                      // dx, world units: the stretch each sample stands for
    std::vector<double> positions;          // distances of the samples from the entry, world units
};

class Rays2D {
public:
    // Throws vri::Error on a study that is not valid or exceeds kMaxRays2D.
    explicit Rays2D(const Study2D& study);
    const Study2D& study() const { return study_; }

    // The ray geometry and the closed-form intensity of every ray, exact for the grid as stored
    // (float): between the lines through the voxel samples the reconstructed field is linear along
    // a ray, and beyond the outermost ones the cell-centred convention clamps it, so each piece is
    // integrated exactly. With node-centred data and f's exactly representable node values, the
    // field is one line along the whole ray, as paper A assumes.
    std::vector<Ray2D> closedForm() const;

    // Paper A eq. (6) with the samples of `placement` at `samplingRate` (samples per voxel), the
    // field reconstructed bilinearly from the grid as a renderer would.
    DiscreteRay discrete(int rayIndex, Placement placement, double samplingRate) const;

    RaySamples samples(int rayIndex, Placement placement, double samplingRate) const;
    // An upper bound on the samples a placement puts on one ray at sampling rate 1: the longest ray
    // through the square crosses sqrt(2) gridSize voxels; a placement may add one sample at each end.
    double samplesPerRayAtRate1() const;

    // At a point of the square's own frame ([-side/2, side/2]^2): f itself, and as the grid
    // reconstructs it.
    double analytic(const glm::dvec2& local) const { return field_(glm::dvec3(local, 0.0)); }
    double field(const glm::dvec2& local) const;

private:
    // A ray's samples as the renderer places them: in texture coordinates of the square.
    struct Schedule {
        glm::dvec3 entry{0.0}, exit{0.0};
        double tNear = 0.0, length = 0.0;  // world units
        SampleSchedule<double> samples;
        double worldPerT = 0.0;            // world units per unit of the schedule's t
    };
    Schedule schedule(int rayIndex, Placement placement, double samplingRate) const;
    // A point of the square's frame in the grid's texture coordinates, in the middle of its one layer.
    glm::dvec3 toTexture(const glm::dvec2& local) const;

    Study2D study_;
    LinearField field_;  // f = (x + side/2) / side over the square, standing for the grid
    Volume grid_;        // f sampled onto gridSize x gridSize x 1 voxels
};

}  // namespace vri
