#pragma once
// Reading the JSON files the tools write (stats, diffs, manifests, reproduce records).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "libvri/util/error.h"

namespace vri {

// The file's JSON; throws vri::Error naming the file when it is missing or not valid JSON.
nlohmann::json readJsonFile(const std::filesystem::path& path);

// The value at a dotted path ("stats.rmse.0": a part that is a number indexes an array); throws
// vri::Error "<file>: has no '<path so far>'" where the path leaves the document.
const nlohmann::json& jsonAtPath(const nlohmann::json& root, const std::string& path, const std::filesystem::path& file);

// nlohmann's message without its "[json.exception.type_error.302] " tag: "type must be string, but is number".
std::string jsonExceptionText(const nlohmann::json::exception& e);

// use(), reading JSON that came from `file`: a missing key or a value of the wrong type (nlohmann's
// exceptions) becomes vri::Error("<file>: <what is wrong>") instead of reaching the user raw.
template <class Use>
decltype(auto) readingJsonOf(const std::filesystem::path& file, Use&& use) {
    try {
        return use();
    } catch (const nlohmann::json::exception& e) {
        throw Error(file.string() + ": " + jsonExceptionText(e));
    }
}

}  // namespace vri
