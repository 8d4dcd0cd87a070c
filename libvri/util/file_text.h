#pragma once
// Reading a whole small file into memory: YAML specs, a step's log, what gnuplot drew.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vri {

// The most bytes a text file may have: 64 MiB, far above any spec, log or JSON document the tools
// write or read, and far below what /dev/zero given as a file would take before memory runs out.
inline constexpr std::size_t kTextFileLimit = std::size_t(64) << 20;

// The file's bytes; nullopt when it is missing, a directory, cannot be read or has more than
// kTextFileLimit bytes.
std::optional<std::string> tryReadFileText(const std::filesystem::path& path);

// The file's bytes; throws vri::Error naming the file: "no such file", "is a directory, expected
// <expected>", "not a regular file, expected <expected>" (one that cannot be read: a socket),
// "more than N bytes, the limit for <expected>" (checked while reading: a FIFO or a device has no
// size beforehand), or "cannot read".
std::string readFileText(const std::filesystem::path& path, std::string_view expected);

}  // namespace vri
