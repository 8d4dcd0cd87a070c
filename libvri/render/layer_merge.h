#pragma once
// vri-merge-tiles --layer: the layers of every brick of one brick grid (vri-render --bricks --brick, each
// with its stats) joined into the whole volume's image (core/brick_layers.h), and its stats record.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/core/image.h"
#include "libvri/io/image_io.h"

namespace vri {

struct LayerFiles {
    std::filesystem::path image, stats;
};

struct MergedLayers {
    Image image;             // RGBA
    nlohmann::json record;   // the first layer's stats record, its brick replaced by the join's account
    ImageMetadata metadata;  // the first layer's EXR attributes, less vri:command
};

// Reads the layers and checks that they are every brick of one grid once, rendered with the same options,
// camera and inputs; throws vri::Error naming the file and what was expected.
MergedLayers mergeLayers(const std::vector<LayerFiles>& layers);

}  // namespace vri
