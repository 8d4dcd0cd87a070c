#pragma once
// Reading a whole small file into memory: YAML specs, a step's log, what gnuplot drew.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vri {

// The file's bytes; nullopt when it is missing, a directory or cannot be read.
std::optional<std::string> tryReadFileText(const std::filesystem::path& path);

// The file's bytes; throws vri::Error naming the file: "no such file", "is a directory, expected
// <expected>", or "cannot read".
std::string readFileText(const std::filesystem::path& path, std::string_view expected);

}  // namespace vri
