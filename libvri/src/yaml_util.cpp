#include "yaml_util.h"

#include <fstream>
#include <sstream>

namespace vri::yaml {

std::string where(const std::string& source, const YAML::Node& node) {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return source;
    return source + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

YAML::Node parse(const std::string& text, const std::string& source) {
    try {
        return YAML::Load(text);
    } catch (const YAML::Exception& e) {
        throw Error(source + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                    ": malformed YAML: " + e.msg);
    }
}

YAML::Node load(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": no such file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), path.string());
}

void requireMap(const YAML::Node& node, const std::string& source, std::string_view what) {
    if (!node.IsMap()) throw Error(where(source, node) + ": " + std::string(what) + " must be a mapping");
}

void requireKeys(const YAML::Node& map, const std::string& source, std::initializer_list<std::string_view> allowed) {
    for (const auto& kv : map) {
        if (!kv.first.IsScalar()) throw Error(where(source, kv.first) + ": keys must be plain names");
        const std::string key = kv.first.as<std::string>();
        bool known = false;
        for (auto a : allowed) known = known || key == a;
        if (known) continue;
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        throw Error(where(source, kv.first) + ": unknown key '" + key + "' (expected one of: " + list + ")");
    }
}

double toDouble(const YAML::Node& node, const std::string& source, std::string_view what) {
    try {
        if (node.IsScalar()) return node.as<double>();
    } catch (const YAML::Exception&) {
    }
    throw Error(where(source, node) + ": " + std::string(what) + " must be a number");
}

bool toBool(const YAML::Node& node, const std::string& source, std::string_view what) {
    try {
        if (node.IsScalar()) return node.as<bool>();
    } catch (const YAML::Exception&) {
    }
    throw Error(where(source, node) + ": " + std::string(what) + " must be true or false");
}

std::string toString(const YAML::Node& node, const std::string& source, std::string_view what) {
    if (!node.IsScalar()) throw Error(where(source, node) + ": " + std::string(what) + " must be a string");
    return node.as<std::string>();
}

}  // namespace vri::yaml
