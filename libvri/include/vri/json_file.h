#pragma once
// Reading the JSON files the tools write (stats, diffs, manifests, reproduce records).
#include <filesystem>

#include <nlohmann/json.hpp>

namespace vri {

// The file's JSON; throws vri::Error naming the file when it is missing or not valid JSON.
nlohmann::json readJsonFile(const std::filesystem::path& path);

}  // namespace vri
