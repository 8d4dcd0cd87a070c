#include "libvri/util/file_text.h"

#include <fstream>

#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

enum class Outcome { Read, Unopened, TooLarge, Failed };

// Reads in chunks and stops one byte past the limit, so that a source without an end (/dev/zero, a
// FIFO whose writer never stops) costs at most the limit.
Outcome readCapped(const fs::path& path, std::string& text) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return Outcome::Unopened;  // an ifstream opens a directory on Linux
    std::ifstream in(path, std::ios::binary);
    if (!in) return Outcome::Unopened;
    char chunk[1 << 16];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
        if (text.size() + std::size_t(in.gcount()) > kTextFileLimit) return Outcome::TooLarge;
        text.append(chunk, std::size_t(in.gcount()));
    }
    return in.bad() ? Outcome::Failed : Outcome::Read;
}

}  // namespace

std::optional<std::string> tryReadFileText(const fs::path& path) {
    std::string text;
    if (readCapped(path, text) != Outcome::Read) return std::nullopt;
    return text;
}

std::string readFileText(const fs::path& path, std::string_view expected) {
    std::string text;
    const Outcome outcome = readCapped(path, text);
    if (outcome == Outcome::Read) return text;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    const std::string irregular = fs::is_regular_file(status) ? "" : "not a regular file, ";
    if (outcome == Outcome::TooLarge)
        throw Error(path.string() + ": " + irregular + "more than " + std::to_string(kTextFileLimit) +
                    " bytes, the limit for " + std::string(expected));
    if (fs::is_directory(status)) throw Error(path.string() + ": is a directory, expected " + std::string(expected));
    if (!fs::exists(status)) throw Error(path.string() + ": no such file");
    if (!irregular.empty()) throw Error(path.string() + ": not a regular file, expected " + std::string(expected));
    throw Error(path.string() + ": cannot read");
}

}  // namespace vri
