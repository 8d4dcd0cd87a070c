#include "libvri/core/rays2d.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "libvri/core/box.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/integrator.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

// Rays sit at the centres of equal angular sectors, symmetric about the view direction.
double Study2D::rayAngleDegrees(int i) const { return -0.5 * fovDegrees + (i + 0.5) * fovDegrees / rays; }

glm::dvec2 Study2D::rayDirection(int i) const {
    const double a = rayAngleDegrees(i) * std::numbers::pi / 180.0;
    return {std::cos(a), std::sin(a)};
}

glm::dvec2 Study2D::toWorld(const glm::dvec2& local) const {
    const double c = std::cos(rotationRadians), s = std::sin(rotationRadians);
    return {c * local.x - s * local.y, s * local.x + c * local.y};
}

glm::dvec2 Study2D::toLocal(const glm::dvec2& world) const {
    const double c = std::cos(rotationRadians), s = std::sin(rotationRadians);
    return {c * world.x + s * world.y, -s * world.x + c * world.y};
}

namespace {

struct LocalRay {
    glm::dvec2 origin, dir;  // in the square's frame
};

LocalRay toLocal(const Study2D& study, int i) { return {study.toLocal(study.eye), study.toLocal(study.rayDirection(i))}; }

std::optional<RayInterval> clip(const Study2D& study, const LocalRay& r) {
    const double h = 0.5 * study.side;
    return clipRay(glm::dvec3(r.origin, 0.0), glm::dvec3(r.dir, 0.0), Box{glm::dvec3(-h, -h, -1.0), glm::dvec3(h, h, 1.0)});
}

// The grid's samples along x (in the square's frame) and the values it stores there. Between the
// lines x = const through them, the bilinear reconstruction of a field that varies with x only is
// linear along any ray; beyond the outermost ones the cell-centred convention clamps it.
struct SampleLines {
    std::vector<double> x, value;
};

SampleLines sampleLines(const Volume& grid, GridConvention convention) {
    const double offset = convention == GridConvention::CellCentred ? 0.5 : 0.0;
    SampleLines lines;
    for (int i = 0; i < grid.dims.x; ++i) {
        lines.x.push_back(grid.origin.x + (i + offset) * grid.spacing.x);
        lines.value.push_back(grid.data<float>()[grid.index(i, 0, 0)]);
    }
    return lines;
}

// The grid's reconstruction written out analytically: linear between neighbouring sample lines,
// constant beyond the outermost ones.
double interpolatedField(const SampleLines& lines, double x) {
    const std::vector<double>& xs = lines.x;
    if (x <= xs.front()) return lines.value.front();
    if (x >= xs.back()) return lines.value.back();
    const std::size_t i = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
    const double w = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
    return (1.0 - w) * lines.value[i - 1] + w * lines.value[i];
}

Study2D validated(const Study2D& s) {
    if (!(s.side > 0.0) || !std::isfinite(s.side)) throw Error("2D study: the square's side must be positive and finite");
    if (s.gridSize < 2) throw Error("2D study: the grid needs at least 2x2 voxels");
    if (s.rays < 1) throw Error("2D study: at least one ray is needed");
    checkedCount("2D study: the fan", {std::uint64_t(s.rays)}, kMaxRays2D, "rays");
    if (!(s.fovDegrees > 0.0 && s.fovDegrees < 180.0)) throw Error("2D study: the field of view must be in (0, 180) degrees");
    if (!std::isfinite(s.eye.x) || !std::isfinite(s.eye.y) || !std::isfinite(s.rotationRadians))
        throw Error("2D study: the eye and the rotation must be finite");
    // Every ray enters the square from outside: the placements measure from the entry point, and an eye inside
    // (or on the border) has none.
    const glm::dvec2 eye = s.toLocal(s.eye);
    if (std::abs(eye.x) <= 0.5 * s.side && std::abs(eye.y) <= 0.5 * s.side)
        throw Error("2D study: the eye " + exactNumber(s.eye.x) + "," + exactNumber(s.eye.y) +
                    " is inside the square (or on its border); it must be outside it");
    return s;
}

LinearField squareField(const Study2D& s) {
    const double h = 0.5 * s.side;
    return {Box{glm::dvec3(-h), glm::dvec3(h)}, glm::ivec3(s.gridSize, s.gridSize, 1)};
}

}  // namespace

Rays2D::Rays2D(const Study2D& study)
    : study_(validated(study)), field_(squareField(study_)), grid_(sampleOntoGrid(field_, study_.convention)) {}

std::vector<Ray2D> Rays2D::closedForm() const {
    const Study2D& study = study_;
    std::vector<Ray2D> out;
    const SampleLines lines = sampleLines(grid_, study.convention);
    for (int i = 0; i < study.rays; ++i) {
        Ray2D ray{i, study.rayAngleDegrees(i), 0.0, 0.0, 0.0};
        const LocalRay r = toLocal(study, i);
        if (const auto seg = clip(study, r)) {
            // Split at the sample lines; f is linear on each piece, so the trapezoid rule is exact.
            std::vector<double> cuts{seg->tNear, seg->tFar};
            if (r.dir.x != 0.0)
                for (double x : lines.x) {
                    const double t = (x - r.origin.x) / r.dir.x;
                    if (t > seg->tNear && t < seg->tFar) cuts.push_back(t);
                }
            std::sort(cuts.begin(), cuts.end());
            double integral = 0.0;
            for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
                const double fa = interpolatedField(lines, r.origin.x + cuts[k] * r.dir.x);
                const double fb = interpolatedField(lines, r.origin.x + cuts[k + 1] * r.dir.x);
                integral += 0.5 * (fa + fb) * (cuts[k + 1] - cuts[k]);
            }
            ray.length = seg->tFar - seg->tNear;
            ray.opticalDepth = 0.5 * integral;
            ray.closedForm = -2.0 * std::expm1(-ray.opticalDepth);
        }
        out.push_back(ray);
    }
    return out;
}

double Rays2D::samplesPerRayAtRate1() const { return std::numbers::sqrt2 * study_.gridSize + 2.0; }

glm::dvec3 Rays2D::toTexture(const glm::dvec2& local) const {
    return glm::dvec3((local + 0.5 * study_.side) / study_.side, 0.5);
}

double Rays2D::field(const glm::dvec2& local) const {
    return GridSampler<float, double>(grid_, study_.convention)(toTexture(local));
}

Rays2D::Schedule Rays2D::schedule(int rayIndex, Placement placement, double samplingRate) const {
    const Study2D& study = study_;
    const LocalRay r = toLocal(study, rayIndex);
    Schedule out;
    const auto seg = clip(study, r);
    if (!seg) return out;
    out.entry = toTexture(r.origin + seg->tNear * r.dir);
    out.exit = toTexture(r.origin + seg->tFar * r.dir);
    out.tNear = seg->tNear;
    out.length = seg->tFar - seg->tNear;
    const glm::dvec3 dim(study.gridSize, study.gridSize, 1.0);
    out.samples = placeSamples<double>(placement, out.entry, out.exit, toTexture(r.origin), dim, samplingRate);
    if (out.samples.tEnd > 0.0) out.worldPerT = out.length / out.samples.tEnd;
    return out;
}

DiscreteRay Rays2D::discrete(int rayIndex, Placement placement, double samplingRate) const {
    const GridSampler<float, double> sample(grid_, study_.convention);
    const Schedule s = schedule(rayIndex, placement, samplingRate);
    if (s.samples.count == 0) return {0.0, 0, 0.0};
    const double dx = s.samples.tIncr * s.worldPerT;
    const glm::dvec3 du = (s.exit - s.entry) / s.samples.tEnd;
    RayAccumulator<double> acc;
    for (std::int64_t k = 0; k < s.samples.count; ++k) {
        const double f = sample(s.entry + s.samples.t(k) * du);
        acc.add(Integrator::Riemann, EmissionModel::Colour, {f, f, f, 0.5 * f}, dx);
    }
    return {acc.r, s.samples.count, dx};
}

RaySamples Rays2D::samples(int rayIndex, Placement placement, double samplingRate) const {
    const Schedule s = schedule(rayIndex, placement, samplingRate);
    RaySamples out;
    out.direction = study_.rayDirection(rayIndex);
    out.entry = study_.eye + s.tNear * out.direction;  // rotating the frame keeps distances along the ray
    out.length = s.length;
    if (s.samples.count == 0) return out;
    out.step = s.samples.tIncr * s.worldPerT;
    for (std::int64_t k = 0; k < s.samples.count; ++k) out.positions.push_back(s.samples.t(k) * s.worldPerT);
    return out;
}

}  // namespace vri
