#include "libvri/util/file_text.h"

#include <fstream>
#include <sstream>

#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

std::optional<std::string> tryReadFileText(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return std::nullopt;  // an ifstream opens a directory on Linux
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return std::nullopt;
    return text.str();
}

std::string readFileText(const fs::path& path, std::string_view expected) {
    if (std::optional<std::string> text = tryReadFileText(path)) return *std::move(text);
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw Error(path.string() + ": is a directory, expected " + std::string(expected));
    if (!fs::exists(path, ec)) throw Error(path.string() + ": no such file");
    throw Error(path.string() + ": cannot read");
}

}  // namespace vri
