#include "libvri/util/json_file.h"

#include <algorithm>
#include <cmath>

#include "libvri/util/file_text.h"
#include "libvri/util/printable.h"

namespace vri {

nlohmann::json readJsonFile(const std::filesystem::path& path) {
    const std::string text = readFileText(path, "a JSON file");
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path.string() + ": not valid JSON: " + jsonExceptionText(e));
    }
}

std::string dottedPath(std::string_view pointer) {
    std::string name(pointer.substr(pointer.empty() ? 0 : 1));
    std::ranges::replace(name, '/', '.');
    return name;
}

std::string jsonExceptionText(const nlohmann::json::exception& e) {
    const std::string text = e.what();
    const std::size_t tagEnd = text.starts_with("[json.exception.") ? text.find("] ") : std::string::npos;
    std::string message = tagEnd == std::string::npos ? text : text.substr(tagEnd + 2);
    // JSON_DIAGNOSTICS puts where the value lies first, as a JSON pointer: "(/steps/3/wall_seconds) type must
    // be ...", written as the dotted path this project's messages use, "steps.3.wall_seconds: type must be ...".
    if (message.starts_with("(/")) {
        const std::size_t close = message.find(") ");
        if (close != std::string::npos) message = dottedPath(message.substr(1, close - 1)) + ": " + message.substr(close + 2);
    }
    return message;
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

long long wholeNumberAt(const nlohmann::json& root, const std::string& path, const std::filesystem::path& file,
                        long long lo, long long hi) {
    const nlohmann::json& v = jsonAtPath(root, path, file);
    if (v.is_number_integer() && !v.is_number_unsigned()) {
        if (const long long n = v.get<long long>(); n >= lo && n <= hi) return n;
    } else if (v.is_number_unsigned()) {
        if (const unsigned long long n = v.get<unsigned long long>(); hi >= 0 && n <= static_cast<unsigned long long>(hi) &&
                                                                    static_cast<long long>(n) >= lo)
            return static_cast<long long>(n);
    } else if (v.is_number_float()) {
        // Only a float that is a whole number within the range, compared as doubles before any cast.
        if (const double d = v.get<double>(); d == std::floor(d) && d >= static_cast<double>(lo) && d <= static_cast<double>(hi))
            return static_cast<long long>(d);
    }
    throw Error(file.string() + ": " + path + ": expected a whole number in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got " + printableShort(v.dump(), 40));
}

}  // namespace vri
