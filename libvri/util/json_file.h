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

// The whole number at a dotted path, within [lo, hi]; throws vri::Error "<file>: <path>: expected a whole
// number in [lo, hi], got <value>" for anything else (a fraction, 1e300, a string), where nlohmann's get<int>
// would wrap or truncate what an edited file holds. The value is quoted shortened.
long long wholeNumberAt(const nlohmann::json& root, const std::string& path, const std::filesystem::path& file,
                        long long lo, long long hi);

// "stats.error_bound.max" for the JSON pointer "/stats/error_bound/max": a place in a file as this project's
// messages and value paths name it.
std::string dottedPath(std::string_view pointer);

// nlohmann's message without its "[json.exception.type_error.302] " tag, where the value lies as a dotted
// path first: "steps.3.wall_seconds: type must be number, but is string".
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
