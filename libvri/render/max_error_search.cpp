#include "libvri/render/max_error_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/core/exact_ray.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace {

// One render of the search, as the stats record it.
struct SearchRender {
    std::string_view what;  // "pilot" or "image"
    int width, height;
    double tolerance, bound, seconds;
};

nlohmann::json toJson(double wanted, const std::vector<SearchRender>& renders) {
    nlohmann::json list = nlohmann::json::array();
    for (const SearchRender& r : renders)
        list.push_back({{"what", r.what},
                        {"size", std::to_string(r.width) + "x" + std::to_string(r.height)},
                        {"tolerance", r.tolerance},
                        {"bound", r.bound},
                        {"seconds", r.seconds}});
    return {{"max_error", wanted}, {"renders", list}};
}

}  // namespace

MaxErrorSearch searchMaxErrorTolerance(RenderBackend& backend, const Scene& scene, const Camera& camera,
                                       const RenderRequest& request) {
    constexpr int kTries = 8;
    constexpr int kPilotDivisor = 4, kPilotFrom = 128;
    constexpr double kPilotGoal = 0.6;  // of E: the image's bound, over 16 times the pixels, comes out larger
    const double wanted = *request.maxError;
    ExactReferenceOptions options = request.exactOptions();
    if (!request.wasGiven("--tolerance")) options.tolerance = wanted;
    std::vector<SearchRender> renders;
    // The largest bound of a render, recorded. Below kGaussTolerance, where rounding sets the bound (about
    // 1e-13 on 8-bit data), it stops following the tolerance, while each render costs a thousand times more
    // than one above: the search ends there once a tighter tolerance cut the bound by less than a quarter of
    // its own factor's decades.
    auto largestBound = [&](const ExactReference& ref, std::string_view what) {
        const double bound = *std::max_element(ref.stats.maxBound.begin(), ref.stats.maxBound.end());
        if (options.tolerance < ExactRay::kGaussTolerance && !renders.empty() && renders.back().what == what) {
            const SearchRender& before = renders.back();
            if (bound > before.bound * std::pow(options.tolerance / before.tolerance, 0.25))
                throw Error("--max-error " + exactNumber(wanted) + ": out of reach: the largest per-pixel bound " +
                            (what == "pilot" ? "of the pilot (the view at a quarter of each side) " : "") +
                            "stopped following the tolerance: " + exactNumber(before.bound) + " at tolerance " +
                            exactNumber(before.tolerance) + ", " + exactNumber(bound) + " at " +
                            exactNumber(options.tolerance) + " (rounding sets a floor near it); ask for a larger error");
        }
        renders.push_back({what, ref.width, ref.height, options.tolerance, bound, ref.stats.seconds});
        return bound;
    };
    // The next tolerance after a bound over E; 0 or subnormal: no tolerance left to ask.
    auto tighten = [&](double bound) {
        const double previous = options.tolerance;
        options.tolerance *= 0.5 * wanted / bound;
        if (!(options.tolerance >= std::numeric_limits<double>::min()))
            throw Error("--max-error " + exactNumber(wanted) + ": out of reach: at tolerance " + exactNumber(previous) +
                        " the largest per-pixel bound is " + exactNumber(bound) +
                        ", and the next tolerance would underflow double; ask for a larger error");
    };
    // A forced --simd target names the Gauss batches, which run from kGaussTolerance up: a search that would
    // render below it stops, rather than record a target that did not run (and options that cannot be given).
    auto render = [&](const Camera& camera) -> const ExactReference& {
        if (!options.simdTarget.empty() && options.tolerance < ExactRay::kGaussTolerance)
            throw Error("--max-error " + exactNumber(wanted) + ": with --simd " + options.simdTarget +
                        " the tolerance must stay at or above " + exactNumber(ExactRay::kGaussTolerance) +
                        ", where the SIMD Gauss batches run; the search needs " + exactNumber(options.tolerance) +
                        (renders.empty() ? std::string()
                                         : " after a largest per-pixel bound of " + exactNumber(renders.back().bound)) +
                        ": ask for a larger error, or leave --simd out");
        return backend.renderExact(scene, camera, options);
    };
    const CameraSpec& view = camera.spec();
    if (!options.region && view.width >= kPilotFrom && view.height >= kPilotFrom) {
        CameraSpec pilot = view;
        pilot.width = (view.width + kPilotDivisor - 1) / kPilotDivisor;
        pilot.height = (view.height + kPilotDivisor - 1) / kPilotDivisor;
        if (const auto c = view.zoomCentre)  // c x pilot / view: exact where c is the frame's edge (x pilot / view is not)
            pilot.zoomCentre = glm::dvec2(c->x * pilot.width / view.width, c->y * pilot.height / view.height);
        const Camera pilotCamera(pilot);
        for (int k = 0; k < kTries; ++k) {  // (a pilot that stays above its goal hands the image its last tolerance)
            const double bound = largestBound(render(pilotCamera), "pilot");
            if (bound <= kPilotGoal * wanted) break;
            tighten(bound);
        }
    }
    double bound = 0;
    for (int k = 0; k < kTries; ++k) {
        const ExactReference& ref = render(camera);
        bound = largestBound(ref, "image");
        if (bound <= wanted) return {options.tolerance, &ref, toJson(wanted, renders)};
        tighten(bound);
    }
    throw Error("--max-error " + exactNumber(wanted) + ": the largest per-pixel bound is still " + exactNumber(bound) +
                " after " + std::to_string(kTries) + " renders of the image (last tolerance " + exactNumber(options.tolerance) +
                (request.wasGiven("--tolerance") ? "); ask for a larger error or start from a smaller --tolerance"
                                                 : "); ask for a larger error"));
}

}  // namespace vri
