#include "libvri/render/layer_merge.h"

#include <set>
#include <tuple>
#include <string>
#include <string_view>

#include <glm/geometric.hpp>

#include "libvri/core/brick_grid.h"
#include "libvri/core/brick_layers.h"
#include "libvri/render/merged_digest_sources.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"

namespace vri {

namespace {

struct Layer {
    Image image;
    nlohmann::json record;
    glm::ivec3 grid{0}, brick{0};
};

glm::ivec3 triple(const nlohmann::json& j) { return {j.at(0).get<int>(), j.at(1).get<int>(), j.at(2).get<int>()}; }

Layer readLayer(const LayerFiles& files) {
    Layer layer{readImage(files.image), readJsonFile(files.stats), {}, {}};
    const std::string stats = files.stats.string();
    try {
        const nlohmann::json& scene = layer.record.at("scene");
        if (!scene.contains("brick"))
            throw Error(stats + ": not a brick's stats (its scene has no brick: render with --bricks and --brick)");
        layer.grid = triple(scene.at("brick").at("grid"));
        layer.brick = triple(scene.at("brick").at("index"));
    } catch (const nlohmann::json::exception& e) {
        throw Error(stats + ": not a vri-render stats record (" + e.what() + ")");
    }
    return layer;
}

// A record's `key` as layers of one render share it: the scene less what is each brick's own.
nlohmann::json comparable(const nlohmann::json& record, const char* key) {
    nlohmann::json value = record.value(key, nlohmann::json());
    if (std::string_view(key) == "scene" && value.is_object()) {
        value.erase("brick");
        value.erase("volume_bytes");
    }
    return value;
}

}  // namespace

MergedLayers mergeLayers(const std::vector<LayerFiles>& files) {
    if (files.empty()) throw Error("--layer: no layer given");
    std::vector<Layer> layers;
    for (const LayerFiles& f : files) layers.push_back(readLayer(f));
    const Layer& first = layers.front();
    const std::string firstStats = files.front().stats.string();
    // Every brick of one grid once, and otherwise one render: what would make the layers' samples another
    // ray's or another scene's.
    std::set<std::tuple<int, int, int>> seen;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const Layer& l = layers[i];
        const std::string stats = files[i].stats.string();
        if (l.grid != first.grid)
            throw Error(stats + ": a brick of the " + brickText(l.grid) + " grid, but " + firstStats + " one of the " +
                        brickText(first.grid) + " grid");
        for (const char* key : {"tool", "build", "inputs", "scene", "transfer_function", "camera", "options", "region"})
            if (comparable(l.record, key) != comparable(first.record, key))
                throw Error(stats + ": its " + key + " differ from " + firstStats +
                            "'s (the layers of one render only)");
        if (!seen.insert({l.brick.x, l.brick.y, l.brick.z}).second)
            throw Error(stats + ": brick " + brickText(l.brick) + " is given twice");
    }
    for (int z = 0; z < first.grid.z; ++z)
        for (int y = 0; y < first.grid.y; ++y)
            for (int x = 0; x < first.grid.x; ++x)
                if (!seen.count({x, y, z}))
                    throw Error("--layer: no layer of brick " + brickText({x, y, z}) + " of the " +
                                brickText(first.grid) + " grid (every brick once)");

    std::vector<const Image*> images;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        images.push_back(&layers[i].image);
        names.push_back(files[i].image.string());
    }
    // The most samples a ray takes, from the scene's grid and the step: the bound's g (brick_layers.h).
    double samples = kSampleLimitPerRay;
    if (const nlohmann::json& o = first.record.value("options", nlohmann::json()); o.contains("sampling_rate")) {
        const glm::dvec3 dims{first.record["scene"]["dims"][0].get<double>(),
                              first.record["scene"]["dims"][1].get<double>(),
                              first.record["scene"]["dims"][2].get<double>()};
        samples = maxSamplesPerRay(glm::length(dims), o["sampling_rate"].get<double>());
    }
    BrickComposite joined = compositeBrickLayers(images, names, samples);

    MergedLayers out{std::move(joined.image), first.record, readImageMetadata(files.front().image)};
    nlohmann::json& record = out.record;
    nlohmann::json& scene = record["scene"] = comparable(first.record, "scene");
    scene["storage"] = "bricks";
    // Each brick's counts and times are its own layer's: the join adds none of them up.
    record.erase("stats");
    record.erase("timing");
    record.erase("warnings");
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < layers.size(); ++i)
        list.push_back({{"image", files[i].image.string()},
                        {"stats", files[i].stats.string()},
                        {"brick", {layers[i].brick.x, layers[i].brick.y, layers[i].brick.z}},
                        {"command", layers[i].record.value("command", nlohmann::json())}});
    record["layers"] = std::move(list);
    std::vector<nlohmann::json> parts;
    for (const Layer& l : layers) parts.push_back(l.record);
    mergeDigestSources(record, parts);
    record["join"] = {{"grid", {first.grid.x, first.grid.y, first.grid.z}},
                      {"bound_max", joined.boundMax},
                      {"bound", "per pixel and channel, against the unbricked render (core/brick_layers.h)"}};
    std::erase_if(out.metadata, [](const auto& kv) { return kv.first == "vri:command" || kv.first == "vri:scene"; });
    out.metadata.emplace_back("vri:scene", scene.dump());
    return out;
}

}  // namespace vri
