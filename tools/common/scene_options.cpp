#include "common/scene_options.h"

#include <memory>
#include <optional>

#include "common/cli.h"
#include "libvri/core/analytic_field.h"
#include "libvri/core/brick_volume.h"
#include "libvri/core/scene_flags.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/render/camera_request.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/input_digest.h"

namespace vri {

void SceneOptions::addTo(CLI::App& app) {
    auto* input = app.add_option_group("input", "what to render (one of)");
    CLI::Option* volume = input
                              ->add_option(scene_flag::volume, volumePath_,
                                           "volume file: .raw, .nhdr, .dat, .vdb (a bare name also in $VRI_DATA_DIR)")
                              ->transform(volumeInDataDir());
    input->add_option(scene_flag::field, field_, "analytic field: linear (paper A's f = (x + 1.5) / 3)");
    input->require_option(1);
    raw_.addTo(app);
    app.add_option(scene_flag::range, range_,
                   "raw value range lo,hi that maps to s = 0..1 (default: the type's range, "
                   "or min..max for float)");
    // A volume file brings its own grid: the field's options would be silently ignored with it.
    app.add_option(scene_flag::fieldDims, fieldDims_, "the grid an analytic field stands for, X,Y,Z")
        ->capture_default_str()
        ->excludes(volume);
    app.add_flag(scene_flag::fieldAsGrid, fieldAsGrid_, "sample the analytic field onto that grid and render the grid")
        ->excludes(volume);
    app.add_option(scene_flag::convention, convention_, "grid convention: cell (texture style) or node (dim - 1)")
        ->capture_default_str();
    app.add_option(scene_flag::tf, tfPath_, "transfer function YAML")->required();
    app.add_option(scene_flag::size, size_, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option(scene_flag::eye, eye_, "camera position X,Y,Z (default: in front of the box, +z)");
    app.add_option(scene_flag::target, target_, "point looked at X,Y,Z (default: box centre)");
    app.add_option(scene_flag::up, up_, "up vector X,Y,Z")->capture_default_str();
    app.add_option(scene_flag::fov, fov_, "vertical field of view, degrees")->capture_default_str();
    app.add_option(scene_flag::zoom, zoom_, "close-up: magnify the frame this many times about --zoom-centre")
        ->capture_default_str();
    app.add_option(scene_flag::zoomCentre, zoomCentre_,
                   "the point zoomed into, X,Y in pixels of the full frame "
                   "(default: the image centre)");
}

void SceneOptions::addBrickOptions(CLI::App& app) {
    CLI::Option* bricks = app.add_option(scene_flag::bricks, bricks_,
                                         "cut the volume into a grid of NX,NY,NZ bricks and render one (--brick): "
                                         "a layer for vri-merge-tiles --layer (docs/conventions/bricks.md)");
    app.add_option(scene_flag::brick, brick_, "the brick I,J,K of --bricks to read and render, from 0,0,0")
        ->needs(bricks);
    bricks->needs(app.get_option(scene_flag::brick));
}

glm::ivec2 SceneOptions::imageSize() const { return parseSize(size_, scene_flag::size); }

std::vector<InputArgument> SceneOptions::inputs() const {
    std::vector<InputArgument> files = volumeInputArguments(scene_flag::volume, volumePath_);
    files.push_back({scene_flag::tf, tfPath_});
    return files;
}

SceneSetup SceneOptions::load() const {
    const glm::ivec2 imageSize = this->imageSize();
    // The camera checks these too; here, before the volume is read, with the option's name.
    if (!validFieldOfView(fov_)) throw Error("--fov: expected degrees in (0, 180), got " + exactNumber(fov_));
    if (!validZoom(zoom_)) throw Error("--zoom: expected a finite factor >= 1, got " + exactNumber(zoom_));
    const GridConvention conv = parseGridConvention(convention_, scene_flag::convention);

    nlohmann::json inputs = nlohmann::json::array();
    std::shared_ptr<Volume> volume;
    std::shared_ptr<SparseVolume> sparse;
    std::optional<LinearField> linear;
    std::shared_ptr<BrickVolume> brick;
    std::optional<ValueRange> range;
    if (!range_.empty()) {
        const glm::dvec2 r = parseRange(range_, scene_flag::range);
        range = ValueRange{r.x, r.y};
    }
    if (!bricks_.empty()) {
        if (volumePath_.empty()) throw Error("--bricks: cuts a volume file (--volume), not an analytic field");
        if (raw_.storage() == VolumeStorage::Sparse) throw Error("--bricks: cuts dense volumes, not --storage sparse");
        brick =
            std::make_shared<BrickVolume>(readBrick(volumePath_, raw_.options(), parseDims(bricks_, scene_flag::bricks),
                                                    parseIndex3(brick_, scene_flag::brick), range));
    } else if (!volumePath_.empty()) {
        raw_.storage();  // checked before the volume is read
        LoadedVolume loaded = raw_.load(volumePath_);
        volume = std::move(loaded.dense);
        sparse = std::move(loaded.sparse);
    } else {
        if (field_ != "linear") throw Error("--field: unknown analytic field '" + field_ + "' (expected linear)");
        linear.emplace();
        linear->dims = parseDims(fieldDims_, scene_flag::fieldDims);
        if (fieldAsGrid_) {
            volume = std::make_shared<Volume>(sampleOntoGrid(*linear, conv));
            linear.reset();
        }
    }
    if (range && !brick) {  // a brick takes it as it is read: its own voxels' min..max is not the volume's
        if (!volume && !sparse) throw Error("--range applies to volumes only");
        (sparse ? sparse->range : volume->range) = *range;
    }
    std::filesystem::path digestRecord;  // where a digest came from, when vri-run recorded it (input_digest.h)
    const InputDigests digests = InputDigests::fromEnvironment();
    const auto digested = [&](const std::string& path) {
        InputDigest digest = digests.of(path);
        if (!digest.record.empty()) digestRecord = digest.record;
        return nlohmann::json{{"path", path}, {"sha512", std::move(digest.sha512)}};
    };
    // The volume and, for a header, the file holding its voxels (filesReadBy): both are what the image comes from.
    if (!volumePath_.empty())
        for (const std::filesystem::path& read : filesReadBy(volumePath_)) inputs.push_back(digested(read.string()));
    Scene scene{volume, linear, conv, loadTransferFunction(tfPath_), sparse, brick};
    inputs.push_back(digested(tfPath_));

    CameraRequest camera;
    camera.size = imageSize;
    camera.fov = fov_;
    camera.zoom = zoom_;
    if (!target_.empty()) camera.target = parseVec3(target_, scene_flag::target);
    if (!eye_.empty()) camera.eye = parseVec3(eye_, scene_flag::eye);
    camera.up = parseVec3(up_, scene_flag::up);
    if (!zoomCentre_.empty()) camera.zoomCentre = parseVec2(zoomCentre_, scene_flag::zoomCentre);
    const CameraSpec spec = camera.spec(scene.box());
    return {std::move(scene), spec, std::move(inputs), std::move(digestRecord)};
}

}  // namespace vri
