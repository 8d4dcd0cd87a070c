// The dataset catalog: parsing with positions in every error, lookup and verification.
#include "libvri/experiment/datasets.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <system_error>

#include "libvri/io/yaml_util.h"
#include "libvri/util/error.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

std::string requiredString(const YAML::Node& entry, const std::string& source, const char* key) {
    const YAML::Node node = entry[key];
    if (!node) throw Error(yaml::where(source, entry) + ": dataset is missing '" + key + "'");
    std::string value = yaml::toString(node, source, key);
    if (value.empty()) throw Error(yaml::where(source, node) + ": '" + key + "' must not be empty");
    return value;
}

std::string optionalString(const YAML::Node& entry, const std::string& source, const char* key) {
    return entry[key] ? yaml::toString(entry[key], source, key) : std::string();
}

// A three-element list of numbers: dims or spacing.
glm::dvec3 parseTriple(const YAML::Node& node, const std::string& source, const std::string& what) {
    if (!node.IsSequence() || node.size() != 3)
        throw Error(yaml::where(source, node) + ": " + what + " must be a list of three numbers [x, y, z]");
    return {yaml::toDouble(node[0], source, what), yaml::toDouble(node[1], source, what),
            yaml::toDouble(node[2], source, what)};
}

// A path inside the data directory: relative, and never climbing out of it.
void requireInsideDataDir(const std::string& file, const YAML::Node& node, const std::string& source) {
    const fs::path path(file);
    const bool climbs = std::any_of(path.begin(), path.end(), [](const fs::path& part) { return part == ".."; });
    if (path.is_absolute() || climbs)
        throw Error(yaml::where(source, node) + ": '" + file + "' must be a path relative to the data directory");
}

bool isSha512Hex(const std::string& text) {
    return text.size() == 128 && std::all_of(text.begin(), text.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

DatasetInfo parseEntry(const YAML::Node& entry, const std::string& source) {
    yaml::requireMap(entry, source, "a dataset");
    yaml::requireKeys(entry, source, {"name", "file", "dims", "type", "byte_order", "spacing", "header",
                                      "header_url", "sha512", "url", "status", "note"});
    DatasetInfo info;
    info.name = requiredString(entry, source, "name");
    info.file = requiredString(entry, source, "file");
    requireInsideDataDir(info.file, entry["file"], source);
    info.url = requiredString(entry, source, "url");
    info.status = requiredString(entry, source, "status");
    if (std::none_of(std::begin(kDatasetStatuses), std::end(kDatasetStatuses),
                     [&](const char* s) { return info.status == s; }))
        throw Error(yaml::where(source, entry["status"]) + ": status '" + info.status +
                    "' is unknown (expected exact, reconstructed or stand-in)");
    info.note = requiredString(entry, source, "note");

    info.sha512 = optionalString(entry, source, "sha512");
    if (!info.sha512.empty() && !isSha512Hex(info.sha512))
        throw Error(yaml::where(source, entry["sha512"]) + ": sha512 must be 128 lowercase hex digits");
    if (info.status == "exact" && info.sha512.empty())
        throw Error(yaml::where(source, entry) + ": dataset '" + info.name +
                    "' is 'exact' but has no sha512 to prove it");

    if (!entry["dims"]) throw Error(yaml::where(source, entry) + ": dataset is missing 'dims'");
    const glm::dvec3 dims = parseTriple(entry["dims"], source, "dims");
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] < 1 || dims[axis] > 1e6 || dims[axis] != std::floor(dims[axis]))
            throw Error(yaml::where(source, entry["dims"][axis]) + ": dims must be positive integers");
        info.dims[axis] = static_cast<int>(dims[axis]);
    }
    const std::string type = requiredString(entry, source, "type");
    info.type = parseVoxelType(type, yaml::where(source, entry["type"]));

    if (entry["byte_order"]) {
        const std::string order = yaml::toString(entry["byte_order"], source, "byte_order");
        if (order == "big") info.order = ByteOrder::Big;
        else if (order != "little")
            throw Error(yaml::where(source, entry["byte_order"]) + ": byte_order '" + order +
                        "' is unknown (expected little or big)");
    }
    if (entry["spacing"]) {
        info.spacing = parseTriple(entry["spacing"], source, "spacing");
        for (int axis = 0; axis < 3; ++axis)
            if (!(info.spacing[axis] > 0) || !std::isfinite(info.spacing[axis]))
                throw Error(yaml::where(source, entry["spacing"][axis]) + ": spacing must be positive");
    }
    info.header = optionalString(entry, source, "header");
    if (!info.header.empty()) requireInsideDataDir(info.header, entry["header"], source);
    info.headerUrl = optionalString(entry, source, "header_url");
    if (!info.headerUrl.empty() && info.header.empty())
        throw Error(yaml::where(source, entry["header_url"]) + ": header_url given without a header");
    return info;
}

std::uintmax_t expectedRawBytes(const DatasetInfo& info) {
    return static_cast<std::uintmax_t>(info.dims.x) * static_cast<std::uintmax_t>(info.dims.y) *
           static_cast<std::uintmax_t>(info.dims.z) * voxelSize(info.type);
}

std::vector<DatasetInfo> catalogFromYaml(const YAML::Node& root, const std::string& source) {
    yaml::requireMap(root, source, "the dataset catalog");
    yaml::requireKeys(root, source, {"datasets"});
    const YAML::Node list = root["datasets"];
    if (!list || !list.IsSequence() || list.size() == 0)
        throw Error(yaml::where(source, list ? list : root) + ": 'datasets' must be a non-empty list");
    std::vector<DatasetInfo> catalog;
    std::set<std::string> names;
    for (const YAML::Node& entry : list) {
        catalog.push_back(parseEntry(entry, source));
        if (!names.insert(catalog.back().name).second)
            throw Error(yaml::where(source, entry["name"]) + ": dataset '" + catalog.back().name +
                        "' is listed twice");
    }
    return catalog;
}

}  // namespace

std::vector<DatasetInfo> parseDatasetCatalog(const std::string& yamlText, const std::string& source) {
    return catalogFromYaml(yaml::parse(yamlText, source), source);
}

bool isDatasetCatalog(const fs::path& yamlPath) {
    try {
        const YAML::Node root = yaml::load(yamlPath);
        return root.IsMap() && root["datasets"] && !root["name"];
    } catch (const Error&) {
        return false;
    }
}

std::vector<DatasetInfo> loadDatasetCatalog(const fs::path& yamlPath) {
    return catalogFromYaml(yaml::load(yamlPath), yamlPath.string());
}

const DatasetInfo& findDataset(const std::vector<DatasetInfo>& catalog, const std::string& name,
                               const std::string& where) {
    for (const DatasetInfo& info : catalog)
        if (info.name == name) return info;
    std::string known;
    for (const DatasetInfo& info : catalog) known += (known.empty() ? "" : ", ") + info.name;
    throw Error(where + ": unknown dataset '" + name + "' (known: " + known + ")");
}

fs::path datasetPath(const DatasetInfo& info, const fs::path& dataDir) {
    return dataDir / (info.header.empty() ? info.file : info.header);
}

RawLayout rawLayout(const DatasetInfo& info) {
    RawLayout layout;
    layout.dims = info.dims;
    layout.type = info.type;
    layout.order = info.order;
    layout.spacing = info.spacing;
    return layout;
}

bool verifyDataset(const DatasetInfo& info, const fs::path& dataDir, std::string* why) {
    auto fail = [&](const std::string& reason) {
        if (why != nullptr) *why = reason;
        return false;
    };
    const fs::path raw = dataDir / info.file;
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(raw, ec);
    if (ec) return fail(raw.string() + ": missing");
    if (bytes != expectedRawBytes(info))
        return fail(raw.string() + ": " + std::to_string(bytes) + " bytes, expected " +
                    std::to_string(expectedRawBytes(info)) + " for " + std::to_string(info.dims.x) + "x" +
                    std::to_string(info.dims.y) + "x" + std::to_string(info.dims.z) + " " +
                    std::string(voxelTypeName(info.type)));
    if (!info.header.empty() && !fs::is_regular_file(dataDir / info.header))
        return fail((dataDir / info.header).string() + ": missing");
    if (!info.sha512.empty()) {
        const std::string digest = sha512File(raw);
        if (digest != info.sha512)
            return fail(raw.string() + ": SHA-512 " + digest.substr(0, 16) + "... differs from the catalog's " +
                        info.sha512.substr(0, 16) + "...");
    }
    if (why != nullptr) why->clear();
    return true;
}

}  // namespace vri
