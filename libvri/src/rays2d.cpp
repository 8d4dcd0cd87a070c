#include "vri/rays2d.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vri/box.h"
#include "vri/error.h"
#include "vri/grid_sampler.h"
#include "vri/integrator.h"

namespace vri {

// Rays sit at the centres of equal angular sectors, symmetric about the view direction.
double Study2D::rayAngleDegrees(int i) const { return -0.5 * fovDegrees + (i + 0.5) * fovDegrees / rays; }

namespace {

struct LocalRay {
    glm::dvec2 origin, dir;  // in the square's frame
};

LocalRay toLocal(const Study2D& study, int i) {
    const double a = study.rayAngleDegrees(i) * std::numbers::pi / 180.0;
    const double c = std::cos(study.rotationRadians), s = std::sin(study.rotationRadians);
    // world = R(rotation) local, so local = R^T world
    auto rotateBack = [c, s](glm::dvec2 v) { return glm::dvec2(c * v.x + s * v.y, -s * v.x + c * v.y); };
    return {rotateBack(study.eye), rotateBack(glm::dvec2(std::cos(a), std::sin(a)))};
}

std::optional<RayInterval> clip(const Study2D& study, const LocalRay& r) {
    const double h = 0.5 * study.side;
    return clipRay(glm::dvec3(r.origin, 0.0), glm::dvec3(r.dir, 0.0), Box{glm::dvec3(-h, -h, -1.0), glm::dvec3(h, h, 1.0)});
}

// The lines x = const through the voxel samples, in the square's frame. Between them the bilinear
// reconstruction of a field that varies with x only is linear along any ray; outside the outermost
// ones the cell-centred convention clamps it to a constant.
std::vector<double> sampleLines(const Study2D& study) {
    const bool cell = study.convention == GridConvention::CellCentred;
    const double spacing = study.side / (cell ? study.gridSize : study.gridSize - 1);
    std::vector<double> xs;
    for (int i = 0; i < study.gridSize; ++i) xs.push_back(-0.5 * study.side + (cell ? i + 0.5 : double(i)) * spacing);
    return xs;
}

// f = (x + side/2) / side at a sample line, as the grid stores it (float).
float storedValue(const Study2D& study, double x) { return static_cast<float>((x + 0.5 * study.side) / study.side); }

// The grid's reconstruction written out analytically: linear between the stored values of
// neighbouring sample lines, constant beyond the outermost ones.
double interpolatedField(const Study2D& study, const std::vector<double>& xs, double x) {
    if (x <= xs.front()) return storedValue(study, xs.front());
    if (x >= xs.back()) return storedValue(study, xs.back());
    const std::size_t i = std::min<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin(), xs.size() - 1);
    const double w = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
    return (1.0 - w) * storedValue(study, xs[i - 1]) + w * storedValue(study, xs[i]);
}

Volume gridOf(const Study2D& study) {
    Volume v({study.gridSize, study.gridSize, 1}, VoxelType::Float32);
    v.range = ValueRange{0.0, 1.0};
    const bool cell = study.convention == GridConvention::CellCentred;
    for (int y = 0; y < study.gridSize; ++y)
        for (int x = 0; x < study.gridSize; ++x) {
            const double u = cell ? (x + 0.5) / study.gridSize : double(x) / (study.gridSize - 1);
            v.data<float>()[v.index(x, y, 0)] = static_cast<float>(u);  // f at the voxel: (x + side/2) / side
        }
    return v;
}

Study2D validated(const Study2D& s) {
    if (!(s.side > 0.0)) throw Error("2D study: the square's side must be positive");
    if (s.gridSize < 2) throw Error("2D study: the grid needs at least 2x2 voxels");
    if (s.rays < 1) throw Error("2D study: at least one ray is needed");
    if (!(s.fovDegrees > 0.0 && s.fovDegrees < 180.0)) throw Error("2D study: the field of view must be in (0, 180) degrees");
    return s;
}

}  // namespace

Rays2D::Rays2D(const Study2D& study) : study_(validated(study)), grid_(gridOf(study_)) {}

std::vector<Ray2D> Rays2D::closedForm() const {
    const Study2D& study = study_;
    std::vector<Ray2D> out;
    const std::vector<double> xs = sampleLines(study);
    for (int i = 0; i < study.rays; ++i) {
        Ray2D ray{i, study.rayAngleDegrees(i), 0.0, 0.0, 0.0};
        const LocalRay r = toLocal(study, i);
        if (const auto seg = clip(study, r)) {
            // Split at the sample lines; f is linear on each piece, so the trapezoid rule is exact.
            std::vector<double> cuts{seg->tNear, seg->tFar};
            if (r.dir.x != 0.0)
                for (double x : xs) {
                    const double t = (x - r.origin.x) / r.dir.x;
                    if (t > seg->tNear && t < seg->tFar) cuts.push_back(t);
                }
            std::sort(cuts.begin(), cuts.end());
            double integral = 0.0;
            for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
                const double fa = interpolatedField(study, xs, r.origin.x + cuts[k] * r.dir.x);
                const double fb = interpolatedField(study, xs, r.origin.x + cuts[k + 1] * r.dir.x);
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

double Rays2D::field(const glm::dvec2& local) const {
    const GridSampler<float, double> sample(grid_, study_.convention);
    return sample(glm::dvec3((local + 0.5 * study_.side) / study_.side, 0.5));
}

Rays2D::Schedule Rays2D::schedule(int rayIndex, Placement placement, double samplingRate) const {
    const Study2D& study = study_;
    const LocalRay r = toLocal(study, rayIndex);
    Schedule out;
    const auto seg = clip(study, r);
    if (!seg) return out;
    const double h = 0.5 * study.side;
    auto tex = [&](glm::dvec2 p) { return glm::dvec3((p + h) / study.side, 0.0); };
    out.entry = tex(r.origin + seg->tNear * r.dir);
    out.exit = tex(r.origin + seg->tFar * r.dir);
    out.tNear = seg->tNear;
    out.length = seg->tFar - seg->tNear;
    const glm::dvec3 dim(study.gridSize, study.gridSize, 1.0);
    out.samples = placeSamples<double>(placement, out.entry, out.exit, tex(r.origin), dim, samplingRate);
    return out;
}

DiscreteRay Rays2D::discrete(int rayIndex, Placement placement, double samplingRate) const {
    const GridSampler<float, double> sample(grid_, study_.convention);
    const Schedule s = schedule(rayIndex, placement, samplingRate);
    if (s.samples.count == 0) return {0.0, 0, 0.0};
    const double dx = s.samples.tIncr * s.length / s.samples.tEnd;
    const glm::dvec3 du = (s.exit - s.entry) / s.samples.tEnd;
    RayAccumulator<double> acc;
    for (std::int64_t k = 0; k < s.samples.count; ++k) {
        glm::dvec3 u = s.entry + s.samples.t(k) * du;
        u.z = 0.5;  // the middle of the grid's single layer
        const double f = sample(u);
        acc.add(Integrator::Riemann, EmissionModel::Colour, {f, f, f, 0.5 * f}, dx);
    }
    return {acc.r, s.samples.count, dx};
}

RaySamples Rays2D::samples(int rayIndex, Placement placement, double samplingRate) const {
    const Schedule s = schedule(rayIndex, placement, samplingRate);
    const double a = study_.rayAngleDegrees(rayIndex) * std::numbers::pi / 180.0;
    RaySamples out;
    out.direction = glm::dvec2(std::cos(a), std::sin(a));
    out.entry = study_.eye + s.tNear * out.direction;  // rotating the frame keeps distances along the ray
    out.length = s.length;
    if (s.samples.count == 0) return out;
    const double toWorld = s.length / s.samples.tEnd;
    out.step = s.samples.tIncr * toWorld;
    for (std::int64_t k = 0; k < s.samples.count; ++k) out.positions.push_back(s.samples.t(k) * toWorld);
    return out;
}

}  // namespace vri
