#pragma once
// A whole file's bytes, for tests that check what a writer left on disk.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace vri::test {

inline std::string readBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace vri::test
