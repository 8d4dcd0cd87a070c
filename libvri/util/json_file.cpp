#include "libvri/util/json_file.h"

#include <algorithm>

#include "libvri/util/file_text.h"

namespace vri {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
    const std::string text = readFileText(path, "a JSON file");
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path.string() + ": not valid JSON: " + jsonExceptionText(e));
    }
}

std::string jsonExceptionText(const nlohmann::json::exception& e) {
    const std::string text = e.what();
    const std::size_t tagEnd = text.starts_with("[json.exception.") ? text.find("] ") : std::string::npos;
    return tagEnd == std::string::npos ? text : text.substr(tagEnd + 2);
}

const nlohmann::json& jsonAtPath(const nlohmann::json& root, const std::string& path, const std::filesystem::path& file) {
    const nlohmann::json* node = &root;
    std::size_t start = 0;
    while (start <= path.size()) {
        const std::size_t end = std::min(path.find('.', start), path.size());
        const std::string part = path.substr(start, end - start);
        const bool isIndex = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
        if (node->is_array() && isIndex && std::stoull(part) < node->size()) node = &(*node)[std::stoull(part)];
        else if (node->is_object() && node->contains(part)) node = &(*node)[part];
        else throw Error(file.string() + ": has no '" + path.substr(0, end) + "'");
        start = end + 1;
    }
    return *node;
}

}  // namespace vri
