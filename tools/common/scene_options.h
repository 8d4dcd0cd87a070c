#pragma once
// The command-line options every tool that renders shares: what is rendered (a volume or an
// analytic field, its grid convention and value range, the transfer function) and the camera.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/cli.h"
#include "common/raw_input_options.h"
#include "libvri/core/camera.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/render_contract.h"
#include "libvri/render/scene_setup.h"

namespace vri {

class SceneOptions {
public:
    // Adds --volume or --field (one of them required), the raw input options, --range, --field-dims,
    // --field-as-grid, --convention, --tf (required), --size, --eye, --target, --up, --fov, --zoom
    // and --zoom-centre to `app`.
    void addTo(CLI::App& app);
    // Adds --bricks and --brick (vri-render's: one brick's layer, docs/conventions/bricks.md).
    void addBrickOptions(CLI::App& app);
    // Checks the options, reads the volume and the transfer function and frames the camera; throws
    // vri::Error naming the option or file that is wrong. The cheap checks come before any reading.
    SceneSetup load() const;
    // The files load() reads (--volume with its data file, --tf), for the check against the outputs.
    std::vector<InputArgument> inputs() const;
    // --size, checked (the first thing load() checks).
    glm::ivec2 imageSize() const;

private:
    std::string volumePath_, field_, tfPath_, range_, fieldDims_ = "5,5,5", bricks_, brick_;
    RawInputOptions raw_;
    std::string convention_ = std::string(gridConventionName(kDefaultConvention)), size_ = "800x600", eye_, target_, up_ = "0,1,0", zoomCentre_;
    double fov_ = 30.0, zoom_ = 1.0;
    bool fieldAsGrid_ = false;
};

}  // namespace vri
