#include "libvri/core/render_contract.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "libvri/core/early_termination.h"
#include "libvri/core/simd_march.h"
#include "libvri/core/simd_target.h"
#include "libvri/core/brick_volume.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/printable.h"

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
        throw Error(what + ": unknown value '" + printable(name) +
                    "' (expected on, off or a SIMD target this CPU and " + "build have: " + simdTargetList() + ")");
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
    if (brick) return gridBox(brick->dims(), brick->voxels.spacing, brick->voxels.origin, convention);
    return volume ? volumeBox(*volume, convention) : field->box;
}

glm::dvec3 Scene::dims() const {
    return glm::dvec3(sparse ? sparse->dims : brick ? brick->dims() : volume ? volume->dims : field->dims);
}

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

void requireBrickable(const RenderOptions& options) {
    if (options.integrator != Integrator::Riemann && options.integrator != Integrator::Composite)
        throw Error("--brick: renders riemann and composite (a brick sums the fixed steps it owns), not " +
                    std::string(integratorName(options.integrator)));
    if (options.precision != Precision::Double)
        throw Error(
            "--brick: renders in double (a float sum's grouping would move the joined image by more "
            "than a useful bound, brick_layers.h)");
    if (options.earlyTermination > 0.0 || options.terminationBound > 0.0)
        throw Error(
            "--brick: early termination needs the transmittance in front of the brick, which a brick "
            "does not know");
    if (options.frames > 1)
        throw Error("--brick: one frame (the mean of frames is taken of joined images, not of layers)");
}

void validateRender(const Scene& scene, const Camera& camera, const RenderOptions& options) {
    if (!(options.samplingRate > 0.0) || !std::isfinite(options.samplingRate))
        throw Error("sampling rate must be positive and finite (step h = 1 / rate > 0), got " +
                    std::to_string(options.samplingRate));
    if (options.tileSize < 1) throw Error("tile size must be at least 1");
    if (!scene.volume && !scene.sparse && !scene.brick && !scene.field)
        throw Error("scene has neither a volume nor an analytic field");
    if (scene.brick) requireBrickable(options);
    // A named target where the packets cannot run would be recorded as asked for and never run (with "on"
    // the scalar path runs, and the stats say so).
    if (options.simd && !options.simdTarget.empty() && packetMethod(options) && !PacketScene::supports(scene, options))
        throw Error("--simd " + options.simdTarget +
                    ": the SIMD packets need a dense volume (not --storage sparse) of 4 "
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
            throw Error(
                "--early-termination auto:" + exactNumber(options.terminationBound) + ": " +
                std::string(integratorName(options.integrator)) + " with steps up to " +
                (std::isfinite(hMax) ? exactNumber(hMax) + " voxels" : std::string("the whole ray (no h_max)")) +
                " at this transfer function's largest tau cannot bound what an ended ray leaves out (" +
                exactNumber(rule.simpsonFactor()) +
                " times its transparency): give --h-max or a transparency threshold");
        }
    }
    const bool preintegrated = options.integrator == Integrator::Preintegrated;
    // A looked-up segment's colour is not bounded by C_max times its alpha (the table interpolates colour
    // and depth apart), so early_termination.h's bounds do not hold for it.
    if (preintegrated && (options.earlyTermination > 0.0 || options.terminationBound > 0.0))
        throw Error(
            "early termination: not available for the preintegrated method (its bound does not hold for "
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
                        " would allow more than " +
                        (inFloat ? "2^22 steps on a ray through this volume in float "
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

}  // namespace vri
