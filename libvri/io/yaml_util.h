#pragma once
// Private helpers for reading YAML with errors that point at file, line and column.
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "libvri/util/error.h"

namespace vri::yaml {

// "source:line:column" of a node (1-based), or just "source" when the node has no position.
std::string where(const std::string& source, const YAML::Node& node);

// The most nodes (scalars, sequences, mappings) a YAML file may hold: a transfer function of
// TransferFunction::kMaxPoints points takes 6 a point, the largest experiment file a few thousand.
constexpr std::size_t kMaxYamlNodes = 200000;

// Parses text; a syntax error becomes vri::Error "source:line:column: malformed YAML: ...", a key
// repeated in one mapping "source:line:column: duplicate key 'k' (first at line N)", a file of more
// than kMaxYamlNodes nodes "source:line:column: more than N YAML nodes ..." (before the tree is built).
YAML::Node parse(const std::string& text, const std::string& source);
YAML::Node load(const std::filesystem::path& path);

// Throws "source:line:column: unknown key 'k' (expected one of: ...)" for a key not in `allowed`.
void requireKeys(const YAML::Node& map, const std::string& source, std::span<const std::string_view> allowed);
inline void requireKeys(const YAML::Node& map, const std::string& source, std::initializer_list<std::string_view> allowed) {
    requireKeys(map, source, std::span(allowed.begin(), allowed.size()));
}
void requireMap(const YAML::Node& node, const std::string& source, std::string_view what);

double toDouble(const YAML::Node& node, const std::string& source, std::string_view what);
// A whole number in [lo, hi], as toDouble reads it (so 099 and 1e1 too, which YAML's int does not take); throws
// "source:line:column: <what> must be a whole number in LO..HI, got <text>" otherwise.
long long toWholeNumber(const YAML::Node& node, const std::string& source, std::string_view what, long long lo,
                        long long hi);
bool toBool(const YAML::Node& node, const std::string& source, std::string_view what);
std::string toString(const YAML::Node& node, const std::string& source, std::string_view what);

}  // namespace vri::yaml
