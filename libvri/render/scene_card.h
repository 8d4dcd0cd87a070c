#pragma once
// The scene card: everything another renderer needs to reproduce the integral vri computes for a scene,
// as one versioned JSON document (docs/scene-card.md explains it with a worked pixel; its JSON Schema is
// docs/scene-card.schema.json). It states the volume and how a voxel value becomes the transfer
// function's scalar s, the grid convention and the trilinear reconstruction, the transfer function and
// its emission model, the camera as vectors, as OpenGL-style matrices and as the ray of pixel (i, j), the
// integration domain and the expected image, and for fixed-step methods the step's unit and each of
// paper A's placements as formulas. A few pixels' rays are worked out in numbers (entry, exit, first
// sample, step), so that an implementation can check itself ray by ray before it compares images.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "libvri/core/render_option_table.h"
#include "libvri/render/scene_setup.h"

namespace vri {

inline constexpr int kSceneCardVersion = 1;

// A copy of the volume's voxels in the card's plain layout (headerless, x fastest, little-endian), for
// renderers that cannot read the volume's own format.
struct SceneCardVoxels {
    std::string path;    // as the card names it
    std::string sha512;  // of the bytes written
    std::uint64_t bytes = 0;
};

// The card of `setup` rendered as `request` asks. Throws vri::Error for a scene no card describes (a
// volume kept sparse: its voxels are not all stored).
nlohmann::json sceneCard(const SceneSetup& setup, const RenderRequest& request,
                         const std::optional<SceneCardVoxels>& voxels = std::nullopt);

// The voxels of `setup`'s dense volume in the card's plain layout.
std::string sceneCardVoxelBytes(const SceneSetup& setup);

// The card and, when `voxelsPath` is not empty, the voxels it names there (their bytes, to be written there).
struct SceneCardFiles {
    nlohmann::json card;
    std::string voxels;
};
SceneCardFiles sceneCardWithVoxels(const SceneSetup& setup, const RenderRequest& request,
                                   const std::string& voxelsPath);

}  // namespace vri
