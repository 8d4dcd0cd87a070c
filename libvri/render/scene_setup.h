#pragma once
// A scene ready to render: what is rendered, the camera that looks at it, and the input files it was
// read from (for provenance). The tools' scene options and Python build one; a RenderJob renders it.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "libvri/core/camera.h"
#include "libvri/core/render_contract.h"

namespace vri {

struct SceneSetup {
    Scene scene;
    CameraSpec camera;
    // [{"path", "sha512"}, ...]: the volume file (if any), then the transfer function; empty for a scene
    // built in memory (Python's arrays), whose record then says what it holds ("scene").
    nlohmann::json inputs = nlohmann::json::array();
    // The record the inputs' digests came from (util/input_digest.h: vri-run's, for the steps it runs);
    // empty where they were computed.
    std::filesystem::path digestRecord;
};

}  // namespace vri
