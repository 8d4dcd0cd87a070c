#include "vri/atomic_file.h"

#include <unistd.h>

#include <fstream>
#include <iostream>

#include "vri/error.h"

namespace vri {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    fs::path dir = path.parent_path();
    if (!dir.empty() && !fs::is_directory(dir)) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) throw Error(path.string() + ": cannot create directory " + dir.string() + ": " + ec.message());
    }
    fs::path tmp = path;
    // Appended piece by piece: `"." + std::string` trips a false -Wrestrict in GCC 12.
    std::string name = ".";
    name += path.stem().string();
    name += ".tmp." + std::to_string(::getpid()) + path.extension().string();
    tmp.replace_filename(name);
    try {
        write(tmp);
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec) throw Error(path.string() + ": cannot rename temporary file into place: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

void writeTextFile(const fs::path& path, const std::string& text) {
    if (path == "-") {
        std::cout << text << std::flush;
        return;
    }
    writeAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw Error(path.string() + ": cannot write");
    });
}

}  // namespace vri
