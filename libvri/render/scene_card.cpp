#include "libvri/render/scene_card.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include <glm/geometric.hpp>

#include "libvri/core/box.h"
#include "libvri/core/camera.h"
#include "libvri/core/grid_sampler.h"
#include "libvri/core/placement.h"
#include "libvri/core/voxel_type.h"
#include "libvri/io/provenance.h"
#include "libvri/render/render_json.h"
#include "libvri/util/error.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace {

using Json = nlohmann::json;

Json triple(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A 4x4 matrix as rows: m[row][column], applied to column vectors (p' = M p).
using Matrix = std::array<std::array<double, 4>, 4>;
Json rows(const Matrix& m) {
    Json j = Json::array();
    for (const auto& row : m) j.push_back(row);
    return j;
}

// OpenGL's lookAt: camera space has the eye at the origin, right along +x, up along +y, looking down -z.
Matrix viewMatrix(const CameraSpec& spec, const CameraBasis& b) {
    const glm::dvec3& e = spec.eye;
    return {{{b.right.x, b.right.y, b.right.z, -glm::dot(b.right, e)},
             {b.up.x, b.up.y, b.up.z, -glm::dot(b.up, e)},
             {-b.forward.x, -b.forward.y, -b.forward.z, glm::dot(b.forward, e)},
             {0.0, 0.0, 0.0, 1.0}}};
}

// OpenGL's perspective (NDC x, y, z in [-1, 1], y up), with the zoom: the image shows the frame's NDC
// window of half-width 1 / zoom about the zoom centre c, so ndc_image = zoom (ndc_frame - c).
Matrix projectionMatrix(const CameraSpec& spec, const CameraBasis& b, double near, double far) {
    const double z = spec.zoom;
    const double cx = 2.0 * b.centre.x / spec.width - 1.0, cy = 1.0 - 2.0 * b.centre.y / spec.height;
    return {{{z / b.tanHalfX, 0.0, z * cx, 0.0},
             {0.0, z / b.tanHalfY, z * cy, 0.0},
             {0.0, 0.0, -(far + near) / (far - near), -2.0 * far * near / (far - near)},
             {0.0, 0.0, -1.0, 0.0}}};
}

// Near and far planes that enclose the box (its corners' depths, widened by 1 %), for rasterising
// renderers that draw the box's faces; a raycaster needs neither.
std::pair<double, double> depthRange(const CameraSpec& spec, const CameraBasis& b, const Box& box) {
    double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                           (corner & 4) ? box.hi.z : box.lo.z);
        const double depth = glm::dot(p - spec.eye, b.forward);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    const double far = farthest > 0.0 ? 1.01 * farthest : 1.0;
    return {std::max(0.99 * nearest, 1e-4 * far), far};
}

Json volumeSection(const SceneSetup& setup, const std::optional<SceneCardVoxels>& voxels) {
    const Scene& scene = setup.scene;
    const Box box = scene.box();
    const glm::ivec3 dims(scene.dims());
    const bool cell = scene.convention == GridConvention::CellCentred;
    const GridIndexing g(dims, scene.convention);
    Json j = {
        {"kind", scene.volume ? "volume" : "analytic"},
        {"dims", {dims.x, dims.y, dims.z}},
        {"box", {{"lo", triple(box.lo)}, {"hi", triple(box.hi)}}},
        {"grid_convention", gridConventionName(scene.convention)},
        {"grid_convention_meaning",
         cell ? "cell-centred (texture style): voxel i is the centre of cell i, at (i + 0.5) / n of the box along "
                "each axis; outside the outermost centres the value is clamped to the edge voxel"
              : "node-centred: voxel i sits at i / (n - 1) of the box; the corner voxels lie on the box's corners"},
        {"texture_from_world", "u = (p - box.lo) / (box.hi - box.lo), componentwise: u in [0, 1]^3 inside the box"},
        {"voxel_index_from_texture",
         {{"scale", triple(g.scale)},
          {"offset", triple(g.offset)},
          {"formula", "x = u * scale - offset, componentwise (voxel i at x = i); then x is clamped to [0, dims - 1]"}}},
    };
    if (!scene.volume) {
        const LinearField& f = *scene.field;
        j["field"] = {{"name", "linear"},
                      {"formula",
                       "s(p) = (p.x - box.lo.x) / (box.hi.x - box.lo.x), evaluated exactly at every point "
                       "(no grid, no interpolation); equivalently s = u.x"},
                      {"grid_dims_for_placement", {f.dims.x, f.dims.y, f.dims.z}}};
        return j;
    }
    const Volume& v = *scene.volume;
    const ValueRange r = v.normalisationRange();
    j["voxel_type"] = voxelTypeName(v.type);
    j["spacing"] = triple(v.spacing);
    j["origin"] = triple(v.origin);
    // The file it was read from ({"path", "sha512"}); null for a volume built in memory (Python's arrays).
    j["source"] = setup.inputs.size() == 2 ? setup.inputs[0] : Json();
    const double offset = cell ? 0.5 : 0.0;
    j["world_from_voxel_index"] = rows({{{v.spacing.x, 0.0, 0.0, v.origin.x + offset * v.spacing.x},
                                         {0.0, v.spacing.y, 0.0, v.origin.y + offset * v.spacing.y},
                                         {0.0, 0.0, v.spacing.z, v.origin.z + offset * v.spacing.z},
                                         {0.0, 0.0, 0.0, 1.0}}});
    j["value_to_s"] = {{"lo", r.lo},
                       {"hi", r.hi},
                       {"inverse_range", r.hi > r.lo ? 1.0 / (r.hi - r.lo) : 0.0},
                       {"formula",
                        "s = (v - lo) * inverse_range, v the trilinearly interpolated voxel value (in the voxels' own "
                        "units, before any normalisation); s is not clamped to [0, 1]"}};
    j["interpolation"] =
        "trilinear on the clamped index x: i = min(floor(x), max(dims - 2, 0)), w = x - i per axis (an axis of one "
        "voxel reads that voxel twice); lerp(a, b, w) = a + w * (b - a), along x first (four lerps), then y (two), "
        "then z (one), in the render's precision";
    Json layout = {{"order", "x fastest, then y, then z: voxel (x, y, z) at index x + dims.x * (y + dims.y * z)"},
                   {"byte_order", "little-endian"},
                   {"header_bytes", 0},
                   {"voxel_type", voxelTypeName(v.type)}};
    if (voxels) {
        layout["file"] = voxels->path;
        layout["sha512"] = voxels->sha512;
        layout["bytes"] = voxels->bytes;
    }
    j["voxels"] = layout;
    return j;
}

Json transferFunctionSection(const TransferFunction& tf, const Json& inputs) {
    Json points = Json::array();
    for (const TransferFunctionPoint& p : tf.points())
        points.push_back({{"s", p.s}, {"r", p.r}, {"g", p.g}, {"b", p.b}, {"tau", p.tau}});
    const bool product = tf.emission() == EmissionModel::ColourTimesExtinction;
    return {{"emission", emissionModelName(tf.emission())},
            {"emission_meaning", product ? "the source term is g(s) = C(s) tau(s) (Max's model as paper B writes it)"
                                         : "the source term is g(s) = C(s) (paper A's analytic study)"},
            {"points", std::move(points)},
            {"interpolation",
             "piecewise linear in s between consecutive points: w = (s - a.s) / (b.s - a.s), value = "
             "a + w * (b - a) per channel; constant beyond the first and the last point; where two "
             "points share s (a jump) the value at that s is the right-hand point's"},
            {"tau_unit", "extinction per world unit of ray length (per voxel where the spacing is 1)"},
            {"colour", "linear, not premultiplied by anything; r, g, b may exceed 1"},
            {"source", inputs.empty() ? Json() : inputs.back()}};
}

Json cameraSection(const CameraSpec& spec, const Box& box) {
    const Camera camera(spec);
    const CameraBasis b = camera.basis();
    const auto [near, far] = depthRange(spec, b, box);
    return {{"eye", triple(spec.eye)},
            {"target", triple(spec.target)},
            {"up", triple(spec.up)},
            {"width", spec.width},
            {"height", spec.height},
            {"fov_y_degrees", spec.fovYDegrees},
            {"fov_x_degrees", 2.0 * std::atan(b.tanHalfX) * 180.0 / std::numbers::pi},
            {"zoom", spec.zoom},
            {"zoom_centre_pixels", {b.centre.x, b.centre.y}},
            {"basis",
             {{"forward", triple(b.forward)},
              {"right", triple(b.right)},
              {"up", triple(b.up)},
              {"formula",
               "forward = normalize(target - eye); right = normalize(forward x up_given); up = right x forward"}}},
            {"tan_half_fov_x", b.tanHalfX},
            {"tan_half_fov_y", b.tanHalfY},
            {"aspect_rule", "tan_half_fov_x = tan_half_fov_y * width / height (square pixels)"},
            {"pixel_centre_rule",
             "pixel (i, j), i the column from the left, j the row from the top (row 0 at the top), "
             "is sampled once, at its centre (i + 0.5, j + 0.5)"},
            {"ray",
             {{"origin", "the eye, for every pixel"},
              {"direction",
               "fx = zoom_centre.x + (i + 0.5 - width / 2) / zoom; fy = zoom_centre.y + (j + 0.5 - height / 2) / zoom; "
               "x = (2 fx / width - 1) tan_half_fov_x; y = (1 - 2 fy / height) tan_half_fov_y; "
               "d = normalize(forward + x right + y up), in double precision"}}},
            {"matrix_convention",
             "OpenGL: rows m[row][column] applied to column vectors; camera space looks down -z with +y up; clip = "
             "projection * view * (p, 1); NDC x right and y up in [-1, 1], pixel (i, j) centre at NDC (2 (i + 0.5) / "
             "width - 1, 1 - 2 (j + 0.5) / height); near and far enclose the box and matter only to rasterisers"},
            {"view_matrix", rows(viewMatrix(spec, b))},
            {"projection_matrix", rows(projectionMatrix(spec, b, near, far))},
            {"near", near},
            {"far", far}};
}

// The placement formulas of paper A's Listings 1-4 as vri evaluates them (placement.h), in texture space.
Json placementFormulas() {
    const char* start = "t_start = t_incr / 2";
    return {
        {"common",
         "entry_u, exit_u: the ray's entry and exit in texture coordinates; L = |exit_u - entry_u| (texture units); "
         "n_vox = |(exit_u - entry_u) * dims| (the ray's length counted in voxels, componentwise product); "
         "rate = 1 / step; t_end = L; sample k at t_k = t_start + k * t_incr (computed directly, never accumulated), "
         "position u_k = entry_u + t_k * du with du = (exit_u - entry_u) / L; each sample stands for "
         "dx = t_incr * (world_length / L) world units, world_length = t_far - t_near"},
        {"eye",
         {{"samples", "n = n_vox * rate (not rounded)"},
          {"t_incr", "L / n"},
          {"t_start", "(1 - fract(|entry_u - eye_u| / t_incr)) * t_incr, eye_u = (eye - box.lo) / (box.hi - box.lo)"},
          {"count", "every k with t_k < L"}}},
        {"entry",
         {{"samples", "n = n_vox * rate (not rounded)"},
          {"t_incr", "L / n"},
          {"t_start", start},
          {"count", "every k with t_k < L"}}},
        {"entry-exit",
         {{"samples", "n = floor(n_vox * rate); no sample when n = 0"},
          {"t_incr", "L / n"},
          {"t_start", start},
          {"count", "n"}}},
        {"entry-exit-corner",
         {{"samples", "n = ceil(rate * |(exit_u - entry_u) * (dims - 1)|); no sample when n = 0"},
          {"t_incr", "L / n"},
          {"t_start", start},
          {"count", "n"}}}};
}

Json methodSection(const Scene& scene, const RenderRequest& request) {
    Json j = {{"settings", toJson(request)}};
    const RenderOptions& o = request.options;
    if (request.exact) {
        j["kind"] = "exact";
        j["meaning"] = "vri's exact method: the integral itself within a per-pixel error bound (paper B's reference)";
        return j;
    }
    j["kind"] = isSimpson(o.integrator) ? "adaptive" : "fixed-step";
    if (isSimpson(o.integrator)) return j;
    const glm::dvec3 dims = scene.dims();
    j["step"] = 1.0 / o.samplingRate;
    j["step_unit"] =
        "voxels: the step is measured on the ray's texture-space segment scaled componentwise by the grid's dims "
        "(dims - 1 for entry-exit-corner), not in world units; on a volume of unequal spacings a step of h voxels is a "
        "different world length along different directions";
    j["samples_per_voxel"] = o.samplingRate;
    j["dims_for_placement"] = triple(dims);
    j["placement"] = placementName(o.placement);
    j["placements"] = placementFormulas();
    if (o.jitter)
        j["jitter"] = {
            {"seed", o.seed},
            {"frames", o.frames},
            {"fraction",
             "j(px, py, seed) = (h >> 8) * 2^-24, h = mix(px ^ mix(py ^ mix(seed))), in 32-bit unsigned arithmetic "
             "(wrapping), px the pixel's column, py its row from the top; mix(x): x ^= x >> 16; x *= 0x7feb352d; "
             "x ^= x >> 15; x *= 0x846ca68b; x ^= x >> 16 (Wellons' lowbias32)"},
            {"t_start", "j * t_incr, in place of the placement's t_start; the count is then every k with t_k < t_end "
                        "for every placement"},
            {"frames_rule",
             "frame f = 0 .. frames - 1 uses seed + f (wrapping past 2^32 - 1); the pixel is the mean of the frames' "
             "float32 values, summed in double in frame order and divided by frames"},
            {"meaning", "each ray's first sample at a random fraction of the step past the entry, uniform on [0, 1) "
                        "over seeds: a renderer with its own random numbers reproduces the expectation, not the bits"}};
    const bool product = scene.transferFunction.emission() == EmissionModel::ColourTimesExtinction;
    j["accumulation"] =
        std::string("front to back from T = 1, C = 0; at each sample, v = tf(s(u_k)): ") +
        (o.integrator == Integrator::Composite
             ? std::string("alpha = 1 - exp(-tau dx) (computed as -expm1(-tau dx)); C += T * ") +
                   (product ? "alpha" : "(tau > 0 ? alpha / tau : dx)") + " * c"
         : o.integrator == Integrator::Preintegrated
             ? "segments from half a step before each sample to half a step after, looked up in a pre-integrated table "
               "(docs/conventions)"
             : std::string("C += T * ") + (product ? "(tau * dx)" : "dx") + " * c") +
        "; T *= exp(-tau dx). The pixel is (C.r, C.g, C.b, 1 - T)";
    return j;
}

// A few pixels' rays in numbers: the corners, the centre and the row above it.
Json workedRays(const SceneSetup& setup, const RenderRequest& request) {
    const Camera camera(setup.camera);
    const Box box = setup.scene.box();
    const glm::dvec3 dims = setup.scene.dims();
    const int w = camera.width(), h = camera.height();
    const glm::ivec2 pixels[] = {{0, 0},         {w - 1, 0},     {0, h - 1},
                                 {w - 1, h - 1}, {w / 2, h / 2}, {w / 2, h / 2 - (h > 1)}};
    const bool fixedStep = !request.exact && !isSimpson(request.options.integrator);
    Json rays = Json::array();
    for (const glm::ivec2& p : pixels) {
        const glm::dvec3 d = camera.direction(p.x, p.y);
        Json ray = {{"pixel", {p.x, p.y}}, {"direction", triple(d)}};
        const std::optional<RayInterval> hit = clipRay(camera.eye(), d, box);
        if (!hit || !(hit->tFar > hit->tNear)) {
            ray["hits_box"] = false;
            rays.push_back(std::move(ray));
            continue;
        }
        const glm::dvec3 entry = box.toTexture(camera.eye() + hit->tNear * d);
        const glm::dvec3 exit = box.toTexture(camera.eye() + hit->tFar * d);
        ray["hits_box"] = true;
        ray["t_near"] = hit->tNear;
        ray["t_far"] = hit->tFar;
        ray["entry_u"] = triple(entry);
        ray["exit_u"] = triple(exit);
        if (fixedStep) {
            const SampleSchedule<double> s =
                placeSamples<double>(request.options.placement, entry, exit, box.toTexture(camera.eye()), dims,
                                     request.options.samplingRate);
            ray["t_end"] = s.tEnd;
            ray["t_start"] = s.tStart;
            ray["t_incr"] = s.tIncr;
            ray["samples"] = s.count;
            ray["dx"] = s.count > 0 ? s.tIncr * ((hit->tFar - hit->tNear) / s.tEnd) : 0.0;
        }
        rays.push_back(std::move(ray));
    }
    return rays;
}

}  // namespace

nlohmann::json sceneCard(const SceneSetup& setup, const RenderRequest& request,
                         const std::optional<SceneCardVoxels>& voxels) {
    const Scene& scene = setup.scene;
    if (scene.sparse)
        throw Error(
            "--describe: the volume is kept sparse (--storage sparse, or auto for a .vdb too large to unpack), "
            "and a scene card describes dense voxels: use --storage dense");
    if (scene.brick) throw Error("--describe: a scene card describes the whole volume: leave out --bricks and --brick");
    const Box box = scene.box();
    Json card = {
        {"format", "vri-scene-card"},
        {"version", kSceneCardVersion},
        {"documentation", "docs/scene-card.md"},
        {"generator", {{"build", buildInfo()}}},
        {"volume", volumeSection(setup, voxels)},
        {"transfer_function", transferFunctionSection(scene.transferFunction, setup.inputs)},
        {"camera", cameraSection(setup.camera, box)},
        {"integration",
         {{"domain",
           "the part of each ray inside the closed box: t in [t_near, t_far], t_near >= 0 (a ray from an eye "
           "inside the box starts at the eye); rays that only touch the box integrate nothing; no other "
           "clipping"},
          {"integral",
           "C = integral over [t_near, t_far] of g(s(t)) T(t) dt, T(t) = exp(-integral from t_near to t of "
           "tau(s(t')) dt'), t in world units along the unit direction; alpha = 1 - T(t_far)"},
          {"s_along_the_ray", "s(t) is the volume's reconstruction (volume.interpolation) at u(eye + t d)"}}},
        {"output",
         {{"channels", {"R", "G", "B", "A"}},
          {"premultiplied", true},
          {"meaning", "R, G, B are the integral C itself (already weighted by opacity: premultiplied), A = 1 - T"},
          {"linear", true},
          {"background", {0.0, 0.0, 0.0, 0.0}},
          {"background_meaning",
           "nothing behind the volume: a ray that misses is (0, 0, 0, 0); composite over a "
           "background B as C + (1 - A) B"},
          {"type", "float32"},
          {"row_order", "row 0 at the top"},
          {"image", "OpenEXR RGBA float (vri-render -o); vri-diff also reads RGB EXR, 8- and 16-bit PNG"}}},
        {"method", methodSection(scene, request)},
        {"worked_rays", workedRays(setup, request)},
    };
    return card;
}

std::string sceneCardVoxelBytes(const SceneSetup& setup) {
    if (setup.scene.brick)
        throw Error("--describe-voxels: a scene card describes the whole volume: leave out --bricks and --brick");
    if (!setup.scene.volume) throw Error("--describe-voxels: the scene is an analytic field, which has no voxels");
    static_assert(std::endian::native == std::endian::little, "the card's voxels are little-endian");
    const std::vector<std::byte>& bytes = setup.scene.volume->bytes;
    return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

SceneCardFiles sceneCardWithVoxels(const SceneSetup& setup, const RenderRequest& request,
                                   const std::string& voxelsPath) {
    if (voxelsPath.empty()) return {sceneCard(setup, request), std::string()};
    std::string bytes = sceneCardVoxelBytes(setup);
    const SceneCardVoxels voxels{voxelsPath, sha512Hex(std::as_bytes(std::span(bytes.data(), bytes.size()))),
                                 bytes.size()};
    return {sceneCard(setup, request, voxels), std::move(bytes)};
}

}  // namespace vri
