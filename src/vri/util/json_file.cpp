#include "vri/util/json_file.h"

#include <fstream>

namespace vri {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw Error(path.string() + ": no such file");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path.string() + ": not valid JSON: " + jsonExceptionText(e));
    }
}

std::string jsonExceptionText(const nlohmann::json::exception& e) {
    const std::string text = e.what();
    const std::size_t tagEnd = text.starts_with("[json.exception.") ? text.find("] ") : std::string::npos;
    return tagEnd == std::string::npos ? text : text.substr(tagEnd + 2);
}

}  // namespace vri
