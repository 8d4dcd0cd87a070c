#pragma once
// The fuzz targets' private directory: parsers that read files (volume headers and the raw data they
// name) get each input written there. One directory per process, removed at exit.
#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace vri::fuzz {

// The directory, created on first use with data.raw in it: 512 bytes, which a header may name as its
// data file (8x8x8 uint8, 8x8x4 uint16, 4x4x8 float, ...).
const std::filesystem::path& scratchDir();

// Writes `size` bytes to scratchDir() / name and returns that path.
std::filesystem::path writeInput(const char* name, const std::uint8_t* data, std::size_t size);

// Writes the input as scratchDir() / name and reads it with readVolume, as the tools read a volume
// given on the command line; a vri::Error (a clean rejection) is swallowed, anything else escapes.
void readInputAsVolume(const char* name, const std::uint8_t* data, std::size_t size);

}  // namespace vri::fuzz
