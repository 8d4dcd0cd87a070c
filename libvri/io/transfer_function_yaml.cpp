// Reading transfer functions from YAML, with positions in every error.
#include "libvri/core/transfer_function.h"

#include "libvri/io/transfer_function_yaml.h"
#include "libvri/io/transfer_function_yaml_node.h"
#include "libvri/io/yaml_util.h"

namespace vri {

namespace {

TransferFunctionPoint parsePoint(const YAML::Node& node, const std::string& source, std::size_t index) {
    const std::string what = "points[" + std::to_string(index) + "]";
    auto num = [&](const YAML::Node& n, const std::string& field) { return yaml::toDouble(n, source, what + "." + field); };
    if (node.IsSequence()) {
        if (node.size() != 5)
            throw Error(yaml::where(source, node) + ": " + what + " must be [s, r, g, b, tau] (5 numbers), got " +
                        std::to_string(node.size()));
        return {num(node[0], "s"), num(node[1], "r"), num(node[2], "g"), num(node[3], "b"), num(node[4], "tau")};
    }
    if (!node.IsMap())
        throw Error(yaml::where(source, node) + ": " + what + " must be {s, color, tau} or [s, r, g, b, tau]");
    yaml::requireKeys(node, source, {"s", "color", "tau"});
    for (const char* key : {"s", "color", "tau"})
        if (!node[key]) throw Error(yaml::where(source, node) + ": " + what + " is missing '" + key + "'");
    const YAML::Node c = node["color"];
    if (!c.IsSequence() || c.size() != 3)
        throw Error(yaml::where(source, c) + ": " + what + ".color must be [r, g, b]");
    return {num(node["s"], "s"), num(c[0], "color[0]"), num(c[1], "color[1]"), num(c[2], "color[2]"),
            num(node["tau"], "tau")};
}

}  // namespace

TransferFunction transferFunctionFromYaml(const YAML::Node& root, const std::string& source) {
    yaml::requireMap(root, source, "a transfer function");
    yaml::requireKeys(root, source, {"emission", "points", "description"});
    EmissionModel emission = EmissionModel::ColourTimesExtinction;
    if (root["emission"]) {
        emission = parseEmissionModel(yaml::toString(root["emission"], source, "emission"),
                                      yaml::where(source, root["emission"]));
    }
    const YAML::Node pts = root["points"];
    if (!pts || !pts.IsSequence() || pts.size() == 0)
        throw Error(yaml::where(source, pts ? pts : root) + ": 'points' must be a non-empty list");
    if (pts.size() > TransferFunction::kMaxPoints)
        throw Error(yaml::where(source, pts) + ": 'points' has " + std::to_string(pts.size()) +
                    " points, more than the limit of " + std::to_string(TransferFunction::kMaxPoints));
    std::vector<TransferFunctionPoint> points;
    points.reserve(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
        points.push_back(parsePoint(pts[i], source, i));
        // Validated here as well, so that the message carries the point's line and column.
        validateTransferFunctionPoint(points[i], i > 0 ? &points[i - 1] : nullptr,
                                      yaml::where(source, pts[i]) + ": points[" + std::to_string(i) + "]");
    }
    return TransferFunction(std::move(points), emission, source);
}

TransferFunction parseTransferFunction(const std::string& yamlText, const std::string& source) {
    return transferFunctionFromYaml(yaml::parse(yamlText, source), source);
}

TransferFunction loadTransferFunction(const std::filesystem::path& path) {
    return transferFunctionFromYaml(yaml::load(path), path.string());
}

}  // namespace vri
