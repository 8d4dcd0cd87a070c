// The Python module `vri` (README, "From Python"): volumes, transfer functions, cameras, the CPU renderer
// with every method, the exact reference with its per-pixel bound, and vri-diff's image comparison, on
// NumPy arrays. The options are the tools': a keyword is a row of the render option table
// (render_option_table.h) or a volume option of volume_read_options.h, its value read as the text a
// command line would give (python_option_text.h), so it is checked by the same code with the same
// message; every vri::Error becomes vri.Error (a ValueError) with that one-line message.
#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include "libvri/render/camera_request.h"
#include "libvri/render/diff_verdict.h"
#include "libvri/render/exact_reference_json.h"
#include "libvri/render/image_compare_json.h"
#include "libvri/render/pixel_mask_for.h"
#include "libvri/render/render_job.h"
#include "libvri/render/render_json.h"
#include "libvri/render/scene_card.h"
#include "numpy_image.h"
#include "python_option_text.h"
#include "libvri/core/analytic_field.h"
#include "libvri/core/camera.h"
#include "libvri/core/cpu_renderer.h"
#include "libvri/core/exact_reference.h"
#include "libvri/core/image_compare.h"
#include "libvri/core/image_metrics.h"
#include "libvri/core/pixel_mask.h"
#include "libvri/core/out_of_range_pixels.h"
#include "libvri/core/render_option_table.h"
#include "libvri/io/volume_lookup.h"
#include "libvri/io/image_io.h"
#include "libvri/io/stored_voxels.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/io/volume_read_options.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/parse.h"
#include "libvri/util/utf8.h"

namespace py = pybind11;

namespace vri {

namespace {

// What is rendered: a volume (from a file or an array) or paper A's analytic linear field.
using Source = std::variant<std::shared_ptr<Volume>, LinearField>;

// The keyword of a table row: its flag without the dashes, '-' read as '_' ("--h-min" -> "h_min").
std::string keywordOf(const RenderOptionRow& row) {
    std::string name(row.flag().substr(2));
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

// The rows vri.render takes: vri-render's, less the timing repeats (one call is one frame: time it from
// Python) and the ray log (a file of its own).
bool takenByRender(const RenderOptionRow& row) {
    static constexpr std::string_view kLeftOut[] = {"--repeat", "--warm-up", "--log-ray"};
    return row.takenBy(RenderTool::Render) && std::ranges::find(kLeftOut, row.flag()) == std::end(kLeftOut);
}

bool takenByReference(const RenderOptionRow& row) { return row.flag() == "--tolerance"; }

// A request from the keywords that are table rows, applied in table order as the tools apply theirs, and
// checked against each other (finishRenderRequest). `others` are the caller's own keywords; any other
// keyword is an error naming the ones there are.
RenderRequest requestFrom(RenderTool tool, bool (*takes)(const RenderOptionRow&), const py::kwargs& kwargs,
                          const std::vector<std::string>& others, const std::string& function) {
    RenderRequest request(tool);
    std::vector<std::string> known = others;
    for (const RenderOptionRow& row : renderOptionTable()) {
        if (!takes(row)) continue;
        const std::string keyword = keywordOf(row);
        known.push_back(keyword);
        if (!kwargs.contains(keyword)) continue;
        row.apply(optionText(kwargs[keyword.c_str()], keyword), keyword, request);
        request.given.push_back(row.flag());
    }
    for (const auto& [key, value] : kwargs) {
        const std::string name = py::str(key);
        if (std::ranges::find(known, name) != known.end()) continue;
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw Error(function + ": unknown keyword '" + name + "' (expected " + list + ")");
    }
    finishRenderRequest(request);
    return request;
}

// vri-render's --threads: worker threads for this call, all cores unless given.
std::optional<int> threadCount(const py::kwargs& kwargs) {
    if (!kwargs.contains("threads") || kwargs["threads"].is_none()) return std::nullopt;
    return parseCount(optionText(kwargs["threads"], "threads"), "threads", 1);
}

bool flagKeyword(const py::kwargs& kwargs, const char* name) {
    return kwargs.contains(name) && kwargs[name].cast<bool>();
}

py::object toPython(const nlohmann::json& record) {
    return py::module_::import("json").attr("loads")(record.dump());
}

CameraRequest makeCamera(const py::object& size, const py::object& eye, const py::object& target,
                         const py::object& up, const py::object& fov, const py::object& zoom,
                         const py::object& zoomCentre) {
    CameraRequest c;
    if (!size.is_none()) {
        std::string text = optionText(size, "size");  // (800, 600) reads as "800,600", the tools' 800x600
        if (!py::isinstance<py::str>(size)) std::replace(text.begin(), text.end(), ',', 'x');
        c.size = parseSize(text, "size");
    }
    if (!eye.is_none()) c.eye = parseVec3(optionText(eye, "eye"), "eye");
    if (!target.is_none()) c.target = parseVec3(optionText(target, "target"), "target");
    if (!up.is_none()) c.up = parseVec3(optionText(up, "up"), "up");
    if (!fov.is_none()) c.fov = parsePositive(optionText(fov, "fov"), "fov");
    if (!zoom.is_none()) c.zoom = parsePositive(optionText(zoom, "zoom"), "zoom");
    if (!zoomCentre.is_none()) c.zoomCentre = parseVec2(optionText(zoomCentre, "zoom_centre"), "zoom_centre");
    Camera(c.spec(Box{glm::dvec3(0.0), glm::dvec3(1.0)}));  // the camera's own checks, now rather than at render
    return c;
}

Scene makeScene(const Source& source, const TransferFunction& tf, const std::string& convention) {
    const GridConvention conv = parseGridConvention(convention, "convention");
    if (const auto* volume = std::get_if<std::shared_ptr<Volume>>(&source)) return Scene{*volume, std::nullopt, conv, tf};
    return Scene{nullptr, std::get<LinearField>(source), conv, tf};
}

// The call as the record's "command" names it: the function and its keywords, each as the text it was read from.
nlohmann::json pythonCall(const std::string& function, const py::kwargs& kwargs) {
    nlohmann::json keywords = nlohmann::json::object();
    for (const auto& [key, value] : kwargs) {
        const std::string name = py::str(key);
        keywords[name] = std::string(py::str(value));
    }
    return {{"python", "vri." + function}, {"keywords", std::move(keywords)}};
}

// vri-render's flow (RenderJob) for one frame: the same checks, backends, --max-error search and record.
py::tuple renderImage(const Source& source, const TransferFunction& tf, const CameraRequest& cameraOptions,
                      const std::string& convention, const py::kwargs& kwargs) {
    RenderRequest request =
        requestFrom(RenderTool::Render, takenByRender, kwargs, {"threads", "allow_nonfinite"}, "render");
    const std::optional<int> threads = threadCount(kwargs);
    Scene scene = makeScene(source, tf, convention);
    const CameraSpec camera = cameraOptions.spec(scene.box());
    const RenderJobContext context{"python", pythonCall("render", kwargs), false, flagKeyword(kwargs, "allow_nonfinite"),
                                   "allow_nonfinite=True"};
    std::optional<RenderResult> result;
    {
        py::gil_scoped_release release;  // other Python threads run while this one renders
        std::optional<tbb::global_control> limit;
        if (threads) limit.emplace(tbb::global_control::max_allowed_parallelism, *threads);
        RenderJob job(std::move(request), SceneSetup{std::move(scene), camera}, context);
        job.searchTolerance();
        RenderFrame frame = job.frame();
        const double seconds = frame.seconds;
        result = job.finish(std::move(frame), frameTimingRecord(0, {seconds}));
    }
    for (const std::string& warning : result->warnings)
        PyErr_WarnEx(PyExc_RuntimeWarning, warning.c_str(), 1);
    nlohmann::json stats = result->record["stats"];
    stats["options"] = result->record["options"];
    stats["record"] = result->record;  // what vri-render's --stats file holds for this render
    return py::make_tuple(toNumpy(result->image), toPython(stats));
}

// vri-render --describe: the scene card of this scene and these options, as a dict.
py::object sceneCardOf(const Source& source, const TransferFunction& tf, const CameraRequest& cameraOptions,
                         const std::string& convention, const py::kwargs& kwargs) {
    const RenderRequest request = requestFrom(RenderTool::Render, takenByRender, kwargs, {}, "describe");
    SceneSetup setup{makeScene(source, tf, convention), {}};
    setup.camera = cameraOptions.spec(setup.scene.box());
    if (!request.exact) validateRender(setup.scene, Camera(setup.camera), request.options);
    return toPython(sceneCard(setup, request));
}

py::tuple exactReference(const Source& source, const TransferFunction& tf, const CameraRequest& cameraOptions,
                         const std::string& convention, const py::kwargs& kwargs) {
    const RenderRequest request = requestFrom(RenderTool::Reference, takenByReference, kwargs, {"threads"}, "reference");
    const std::optional<int> threads = threadCount(kwargs);
    const Scene scene = makeScene(source, tf, convention);
    const Camera camera(cameraOptions.spec(scene.box()));
    std::optional<ExactReference> ref;
    {
        py::gil_scoped_release release;
        std::optional<tbb::global_control> limit;
        if (threads) limit.emplace(tbb::global_control::max_allowed_parallelism, *threads);
        ref = renderExactReference(scene, camera, request.exactOptions());
    }
    nlohmann::json stats = toJson(ref->stats);
    stats["options"] = toJson(request);
    return py::make_tuple(toNumpy(ref->values, ref->width, ref->height, 4),
                          toNumpy(ref->bounds, ref->width, ref->height, 4), toPython(stats));
}

std::shared_ptr<Volume> loadVolume(const std::string& path, const py::object& dims, const py::object& type,
                                   const py::object& byteOrder, const py::object& headerBytes,
                                   const py::object& spacing, const py::object& grid, const py::object& range) {
    VolumeReadOptions options;
    if (!dims.is_none()) options.dims = optionText(dims, "dims");
    if (!type.is_none()) options.type = optionText(type, "type");
    if (!byteOrder.is_none()) options.byteOrder = optionText(byteOrder, "byte_order");
    if (!headerBytes.is_none()) options.headerBytes = parseCount(optionText(headerBytes, "header_bytes"), "header_bytes", 0);
    if (!spacing.is_none()) options.spacing = optionText(spacing, "spacing");
    if (!grid.is_none()) options.grid = optionText(grid, "grid");
    std::optional<ValueRange> valueRange;  // checked before the file is read
    if (!range.is_none()) {
        const glm::dvec2 r = parseRange(optionText(range, "range"), "range");
        valueRange = ValueRange{r.x, r.y};
    }
    auto volume = std::make_shared<Volume>(readVolume(findVolume(path, ".").value_or(path), options));
    if (valueRange) volume->range = valueRange;
    return volume;
}

// A volume of an array indexed [z, y, x] (x fastest, as vri stores voxels). uint8, uint16 and float32 are
// kept; every other type a volume file may store (int8, int16, int32, uint32, float64, NumPy's default) by the
// formats' one rule (libvri/io/stored_voxels.h): float64 rounded to the nearest float32, a value beyond
// float32's range refused; integers to the nearest float, normalised over their type's full range.
std::shared_ptr<Volume> volumeFromArray(const py::array& array, const py::object& spacing, const py::object& origin,
                                        const py::object& range) {
    if (array.ndim() != 3)
        throw Error("array: expected 3 dimensions [z, y, x], got " + std::to_string(array.ndim()) +
                    (array.ndim() == 2 ? " (one 2-D slice is array[None], a volume of depth 1)" : ""));
    const py::dtype dtype = array.dtype();
    const std::pair<py::dtype, detail::StoredType> types[] = {
        {py::dtype::of<std::uint8_t>(), detail::StoredType::UInt8},   {py::dtype::of<std::uint16_t>(), detail::StoredType::UInt16},
        {py::dtype::of<float>(), detail::StoredType::Float32},        {py::dtype::of<double>(), detail::StoredType::Float64},
        {py::dtype::of<std::int8_t>(), detail::StoredType::Int8},     {py::dtype::of<std::int16_t>(), detail::StoredType::Int16},
        {py::dtype::of<std::int32_t>(), detail::StoredType::Int32},   {py::dtype::of<std::uint32_t>(), detail::StoredType::UInt32}};
    const auto found = std::find_if(std::begin(types), std::end(types), [&](const auto& t) { return dtype.is(t.first); });
    if (found == std::end(types))
        throw Error("array: expected uint8, uint16 or float32 voxels (kept), or int8, int16, int32, uint32 or float64 "
                    "(converted to float32), in native byte order; got " +
                    py::str(py::handle(dtype)).cast<std::string>());
    glm::ivec3 dims;
    for (int axis = 0; axis < 3; ++axis) {
        const py::ssize_t n = array.shape(2 - axis);
        if (n > std::numeric_limits<int>::max()) throw Error("array: " + std::to_string(n) + " voxels along an axis");
        dims[axis] = int(n);
    }
    // The size is checked against vri's limit before NumPy is asked for a contiguous copy (a broadcast view
    // of a few bytes can stand for terabytes), and a copy NumPy cannot make is an error, not a null array.
    const std::size_t bytes = checkedBytes("array", {std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z),
                                                     detail::storedSize(found->second)});
    const auto contiguous = py::array::ensure(array, py::array::c_style);
    if (!contiguous) {
        PyErr_Clear();
        throw Error("array: NumPy could not make a contiguous copy of its " + std::to_string(bytes) +
                    " bytes (out of memory?)");
    }
    auto volume = std::make_shared<Volume>(detail::decodeVoxels(
        "array", dims, found->second, nativeByteOrder(),
        std::string_view(static_cast<const char*>(contiguous.data()), bytes)));
    if (!spacing.is_none()) volume->spacing = parseVec3(optionText(spacing, "spacing"), "spacing");
    if (!origin.is_none()) volume->origin = parseVec3(optionText(origin, "origin"), "origin");
    if (!range.is_none()) {
        const glm::dvec2 r = parseRange(optionText(range, "range"), "range");
        volume->range = ValueRange{r.x, r.y};
    }
    if (!(volume->spacing.x > 0 && volume->spacing.y > 0 && volume->spacing.z > 0))
        throw Error("spacing: expected positive numbers");
    requireUsableValues(*volume, "array");
    return volume;
}

py::array voxelArray(const Volume& volume) {
    const std::vector<py::ssize_t> shape{volume.dims.z, volume.dims.y, volume.dims.x};
    py::array array;
    switch (volume.type) {
    case VoxelType::UInt8: array = py::array_t<std::uint8_t>(shape); break;
    case VoxelType::UInt16: array = py::array_t<std::uint16_t>(shape); break;
    case VoxelType::Float32: array = py::array_t<float>(shape); break;
    }
    std::memcpy(array.mutable_data(), volume.bytes.data(), volume.byteCount());
    return array;
}

TransferFunction transferFunctionFromArray(const py::object& points, const std::string& emission) {
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
    if (!array || array.ndim() != 2 || array.shape(1) != 5 || array.shape(0) < 1)
        throw Error("points: expected an array of rows s, r, g, b, tau (shape (N, 5), N >= 1)");
    std::vector<TransferFunctionPoint> list;
    for (py::ssize_t i = 0; i < array.shape(0); ++i)
        list.push_back({array.at(i, 0), array.at(i, 1), array.at(i, 2), array.at(i, 3), array.at(i, 4)});
    return TransferFunction(std::move(list), parseEmissionModel(emission, "emission"), "points");
}

py::array_t<double> pointArray(const TransferFunction& tf) {
    py::array_t<double> array({py::ssize_t(tf.points().size()), py::ssize_t(5)});
    auto out = array.mutable_unchecked<2>();
    for (std::size_t i = 0; i < tf.points().size(); ++i) {
        const TransferFunctionPoint& p = tf.points()[i];
        const double row[5] = {p.s, p.r, p.g, p.b, p.tau};
        for (int c = 0; c < 5; ++c) out(py::ssize_t(i), c) = row[c];
    }
    return array;
}

py::tuple vec3(const glm::dvec3& v) { return py::make_tuple(v.x, v.y, v.z); }

// "(1, 2.5, 3)": a tuple as Python prints it, for the reprs.
std::string tupleText(const py::tuple& t) { return py::repr(t).cast<std::string>(); }

double requireNonNegative(double value, const char* name) {
    if (!(value >= 0)) throw Error(std::string(name) + ": expected a number >= 0, got " + exactNumber(value));
    return value;
}

double requirePercent(double value, const char* name) {
    if (!(value >= 0 && value <= 100)) throw Error(std::string(name) + ": expected a percentage in [0, 100], got " + exactNumber(value));
    return value;
}

}  // namespace

}  // namespace vri

PYBIND11_MODULE(vri, m) {
    using namespace vri;
    m.doc() = "vri: volume rendering integrals, rendered and measured (README.md, \"From Python\")";
    m.attr("__version__") = VRI_VERSION;
    // vri.Error, its message made well-formed UTF-8 first: Python decodes it as UTF-8, and a message naming a
    // path of other bytes (load_volume(b"\xff.raw")) would otherwise arrive empty.
    static py::exception<Error> errorType(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const Error& e) {
            errorType(escapeInvalidUtf8(e.what()).c_str());
        }
    });

    py::class_<Volume, std::shared_ptr<Volume>>(m, "Volume", "A regular scalar volume in its native voxel type")
        .def_static("from_array", &volumeFromArray, py::arg("array"), py::kw_only(), py::arg("spacing") = py::none(),
                    py::arg("origin") = py::none(), py::arg("range") = py::none(),
                    "A volume of a [z, y, x] array (copied): uint8, uint16 and float32 kept; int8, int16, int32, uint32 "
                    "and float64 (NumPy's default) converted to float32 as the volume formats' rule (README, "
                    "\"Formats\"): float64 rounded to the nearest float32, a value beyond its range refused")
        .def_property_readonly("dims", [](const Volume& v) { return py::make_tuple(v.dims.x, v.dims.y, v.dims.z); })
        .def_property_readonly("spacing", [](const Volume& v) { return vec3(v.spacing); })
        .def_property_readonly("origin", [](const Volume& v) { return vec3(v.origin); },
                               "the box's min corner (README, \"Formats\")")
        .def_property_readonly("voxel_type", [](const Volume& v) { return std::string(voxelTypeName(v.type)); })
        .def_property_readonly("range",
                               [](const Volume& v) -> py::object {
                                   if (!v.range) return py::none();
                                   return py::make_tuple(v.range->lo, v.range->hi);
                               })
        .def("values", &voxelArray, "the voxels as a [z, y, x] array (a copy)")
        .def("__repr__", [](const Volume& v) {
            std::string text = "vri.Volume(dims=" + tupleText(py::make_tuple(v.dims.x, v.dims.y, v.dims.z)) +
                               ", voxel_type='" + std::string(voxelTypeName(v.type)) + "', spacing=" +
                               tupleText(vec3(v.spacing)) + ", origin=" + tupleText(vec3(v.origin));
            if (v.range) text += ", range=" + tupleText(py::make_tuple(v.range->lo, v.range->hi));
            return text + ")";
        });

    py::class_<LinearField>(m, "LinearField", "Paper A's analytic field f = (x + 1.5) / 3 on the box [-1.5, 1.5]^3")
        .def(py::init([](const py::object& dims) {
                 LinearField field;
                 field.dims = parseDims(optionText(dims, "dims"), "dims");
                 return field;
             }),
             py::arg("dims") = py::make_tuple(5, 5, 5), "the grid it stands for (vri-render's --field-dims)")
        .def("sample_onto_grid",
             [](const LinearField& f, const std::string& convention) {
                 return std::make_shared<Volume>(sampleOntoGrid(f, parseGridConvention(convention, "convention")));
             },
             py::arg("convention") = "cell", "the field sampled onto its grid (vri-render's --field-as-grid)")
        .def("__repr__", [](const LinearField& f) {
            return "vri.LinearField(dims=" + tupleText(py::make_tuple(f.dims.x, f.dims.y, f.dims.z)) + ")";
        });

    m.def("load_volume", &loadVolume, py::arg("path"), py::kw_only(), py::arg("dims") = py::none(),
          py::arg("type") = py::none(), py::arg("byte_order") = py::none(), py::arg("header_bytes") = py::none(),
          py::arg("spacing") = py::none(), py::arg("grid") = py::none(), py::arg("range") = py::none(),
          "Reads any volume file vri reads (README, \"Formats\"); a relative path that is not here is looked up in "
          "$VRI_DATA_DIR. With the tools' --dims, --type, --byte-order, "
          "--header-bytes, --spacing, --grid (vri-convert) and --range");

    py::class_<TransferFunction>(m, "TransferFunction", "A piecewise-linear transfer function s -> r, g, b, tau")
        .def(py::init(&transferFunctionFromArray), py::arg("points"), py::arg("emission") = "color-times-extinction",
             "From rows s, r, g, b, tau (sorted by s) and the emission model (color-times-extinction or color)")
        .def_property_readonly("points", &pointArray, "rows s, r, g, b, tau")
        .def_property_readonly("emission", [](const TransferFunction& tf) { return std::string(emissionModelName(tf.emission())); })
        .def("__repr__", [](const TransferFunction& tf) {
            const auto& p = tf.points();
            return "vri.TransferFunction(" + std::to_string(p.size()) + " points, s from " + exactNumber(p.front().s) +
                   " to " + exactNumber(p.back().s) + ", emission='" + std::string(emissionModelName(tf.emission())) + "')";
        });
    m.def("load_transfer_function", [](const std::string& path) { return loadTransferFunction(path); },
          py::arg("path"), "Reads a transfer-function YAML file (vri-render's --tf)");
    m.def("parse_transfer_function", [](const std::string& text) { return parseTransferFunction(text, "yaml"); },
          py::arg("text"), "Reads a transfer function from YAML text");

    py::class_<CameraRequest>(m, "Camera", "A pinhole camera, as vri-render's camera options give it")
        .def(py::init(&makeCamera), py::kw_only(), py::arg("size") = py::none(), py::arg("eye") = py::none(),
             py::arg("target") = py::none(), py::arg("up") = py::none(), py::arg("fov") = py::none(),
             py::arg("zoom") = py::none(), py::arg("zoom_centre") = py::none(),
             "size (width, height) or 'WxH' (default 800x600); eye and target default to the tools' framing of "
             "the box (in front of it, +z, looking at its centre); up (0, 1, 0); fov 30 degrees, vertical")
        .def_property_readonly("size", [](const CameraRequest& c) { return py::make_tuple(c.size.x, c.size.y); })
        .def_property_readonly("fov", [](const CameraRequest& c) { return c.fov; })
        .def("__repr__", [](const CameraRequest& c) {
            std::string text = "vri.Camera(size=" + tupleText(py::make_tuple(c.size.x, c.size.y));
            if (c.eye) text += ", eye=" + tupleText(vec3(*c.eye));
            if (c.target) text += ", target=" + tupleText(vec3(*c.target));
            return text + ", up=" + tupleText(vec3(c.up)) + ", fov=" + exactNumber(c.fov) + ")";
        });

    const char* renderHelp =
        "render(source, tf, camera, convention='cell', **options) -> (image, stats)\n"
        "source: a Volume or a LinearField; image: float32 array (height, width, 4), premultiplied RGBA, row 0 at "
        "the top, vri-render's EXR bit for bit; stats: the 'stats' of vri-render's stats record as a dict, with "
        "'options' and 'record' (the whole provenance record, what vri-render --stats writes for this render).\n"
        "options: vri-render's render options as keywords (method, step, rate, precision, simd, early_termination, "
        "tolerance, max_error, h0, h_min, h_max, accepted_value, no_skip_empty, clamp, backend, device, "
        "interpolation, ...), threads, allow_nonfinite. The same flow as vri-render (RenderJob): backend='vulkan' "
        "renders on the Vulkan device, max_error=E searches the exact method's tolerance. Warnings are Python "
        "RuntimeWarnings. The GIL is released while it renders.";
    m.def("render", &renderImage, py::arg("source"), py::arg("tf"), py::arg("camera") = CameraRequest{},
          py::arg("convention") = "cell", renderHelp);
    m.def("describe", &sceneCardOf, py::arg("source"), py::arg("tf"), py::arg("camera") = CameraRequest{},
          py::arg("convention") = "cell",
          "describe(source, tf, camera, convention='cell', **options) -> dict\nvri-render --describe: the scene card "
          "(docs/scene-card.md), everything another renderer needs to reproduce this render's integral; renders "
          "nothing. options: as render()'s.");
    m.def("reference", &exactReference, py::arg("source"), py::arg("tf"), py::arg("camera") = CameraRequest{},
          py::arg("convention") = "cell",
          "reference(source, tf, camera, convention='cell', tolerance=1e-13, threads=None) -> (values, bounds, "
          "stats)\nvri-reference's exact method: the values and their per-pixel error bounds as float64 arrays "
          "(height, width, 4), and its stats as a dict. The GIL is released while it renders.");

    m.def("compare",
          [](const py::object& a, const py::object& b, const std::vector<double>& thresholds, double fail,
             double failPercent, double warn, double warnPercent, bool perPixel, const std::string& maskText,
             bool withHdrFlip) {
              const Image reference = fromNumpy(a, "a");  // a's shape is checked first
              const Image other = fromNumpy(b, "b");
              const DiffLimits limits{requireNonNegative(fail, "fail"), requirePercent(failPercent, "failpercent"),
                                      requireNonNegative(warn, "warn"), requirePercent(warnPercent, "warnpercent"),
                                      perPixel};
              requireSameShape(reference, other);
              for (const double t : thresholds)
                  if (!(t >= 0) || !std::isfinite(t))
                      throw Error("thresholds: expected numbers >= 0, got " + exactNumber(t));
              const PixelMask mask = pixelMaskFor(parseMaskSpec(maskText), reference, other);
              nlohmann::json record = toJson(compareImages(reference, other, thresholds, &mask));
              record["metrics"] = toJson(imageMetrics(reference, other, &mask, withHdrFlip));
              addVerdict(record, diffVerdict(reference, other, limits, &mask));
              return toPython(record);
          },
          py::arg("a"), py::arg("b"), py::arg("thresholds") = vri::kDefaultThresholds, py::kw_only(),
          py::arg("fail") = DiffLimits{}.fail, py::arg("failpercent") = DiffLimits{}.failPercent,
          py::arg("warn") = DiffLimits{}.warn, py::arg("warnpercent") = DiffLimits{}.warnPercent,
          py::arg("per_pixel") = false, py::arg("mask") = "all", py::arg("hdr_flip") = false,
          "vri-diff's --json record of |a - b| per channel as a dict, a the reference, with its image metrics "
          "('metrics': PSNR, SSIM, relative MSE, SMAPE and 'flip': LDR-FLIP, and HDR-FLIP with hdr_flip=True, as "
          "vri-diff --hdr-flip) and its verdict: 'verdict' (pass, warn or fail), 'exit_code' "
          "(vri-diff's: 0, 2 or 3) and the 'fail' and 'warn' counts, from vri-diff's --fail, --failpercent, --warn, "
          "--warnpercent, --per-pixel and --mask (all, hit, alpha>T or a mask image's path)");
    m.def("read_image", [](const std::string& path) { return toNumpy(readImage(path)); }, py::arg("path"),
          "An image file (EXR, PNG, ...) as a float32 array (height, width, channels)");
    m.def("write_exr", [](const std::string& path, const py::object& image) { writeExr(path, fromNumpy(image, "image")); },
          py::arg("path"), py::arg("image"), "Writes a float RGBA OpenEXR file (atomically)");
    m.def("write_png", [](const std::string& path, const py::object& image) { writePng(path, fromNumpy(image, "image")); },
          py::arg("path"), py::arg("image"), "Writes vri-render's 8-bit sRGB preview PNG (atomically)");
}
