#include "libvri/io/tiff_page_chain.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

#include "libvri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// The file's bytes as TIFF's integers in the byte order its header names, every read checked against
// the file's length.
class TiffBytes {
public:
    explicit TiffBytes(const fs::path& path) : path_(path), in_(path, std::ios::binary), size_(fs::file_size(path)) {
        if (!in_) throw Error(path.string() + ": cannot open");
    }
    std::uint64_t size() const { return size_; }
    void setLittleEndian(bool little) { little_ = little; }
    // The `bytes`-byte unsigned integer at `offset`, or nullopt when it lies beyond the file's end.
    std::optional<std::uint64_t> read(std::uint64_t offset, int bytes) {
        if (offset > size_ || size_ - offset < std::uint64_t(bytes)) return std::nullopt;
        std::array<unsigned char, 8> b{};
        in_.seekg(static_cast<std::streamoff>(offset));
        in_.read(reinterpret_cast<char*>(b.data()), bytes);
        if (!in_) throw Error(path_.string() + ": read failed at byte " + std::to_string(offset));
        std::uint64_t value = 0;
        for (int i = 0; i < bytes; ++i) value |= std::uint64_t(b[little_ ? i : bytes - 1 - i]) << (8 * i);
        return value;
    }

private:
    fs::path path_;
    std::ifstream in_;
    std::uint64_t size_;
    bool little_ = true;
};

}  // namespace

int tiffPageCount(const fs::path& path) {
    TiffBytes file(path);
    const std::string name = path.string();
    const auto order = file.read(0, 2);
    if (!order || (*order != 0x4949 && *order != 0x4d4d))
        throw Error(name + ": not a TIFF file (expected II or MM as its first bytes)");
    file.setLittleEndian(*order == 0x4949);
    const auto version = file.read(2, 2);
    if (!version || (*version != 42 && *version != 43))
        throw Error(name + ": not a TIFF file (expected version 42, or 43 for BigTIFF)");
    const bool big = *version == 43;
    // Classic: 2-byte entry count, 12-byte entries, 4-byte offsets; BigTIFF: 8, 20, 8.
    const int countBytes = big ? 8 : 2, entryBytes = big ? 20 : 12, offsetBytes = big ? 8 : 4;
    std::optional<std::uint64_t> ifd = file.read(big ? 8 : 4, offsetBytes);
    if (!ifd)
        throw Error(name + ": the header ends at byte " + std::to_string(file.size()) + ", before its first page");
    int pages = 0;
    // A chain that loops back never ends: Brent's test finds the loop within twice its length, keeping
    // one directory offset (renewed at each power of two of pages) to compare with.
    std::uint64_t saved = *ifd;
    int power = 1, sinceSaved = 0;
    while (*ifd != 0) {
        if (pages == kMaxTiffPages)
            throw Error(name + ": the chain of pages goes on past " + std::to_string(kMaxTiffPages) +
                        " pages, the limit");
        const std::string where =
            name + ": page " + std::to_string(pages) + ": its directory at byte " + std::to_string(*ifd);
        const auto entries = file.read(*ifd, countBytes);
        if (!entries) throw Error(where + " lies beyond the file's end (" + std::to_string(file.size()) + " bytes)");
        // Both terms stay far below 2^64: entries < 2^64 / 20 is checked first.
        if (*entries > file.size() / std::uint64_t(entryBytes))
            throw Error(where + " claims " + std::to_string(*entries) + " entries, more than the file's " +
                        std::to_string(file.size()) + " bytes hold");
        const std::uint64_t next = *ifd + std::uint64_t(countBytes) + *entries * std::uint64_t(entryBytes);
        ifd = file.read(next, offsetBytes);
        if (!ifd)
            throw Error(where + " (" + std::to_string(*entries) + " entries) ends beyond the file's end (" +
                        std::to_string(file.size()) + " bytes)");
        ++pages;
        if (*ifd == saved)
            throw Error(name + ": page " + std::to_string(pages) + ": its directory at byte " + std::to_string(*ifd) +
                        " is an earlier page's (the chain of pages loops)");
        if (++sinceSaved == power) {
            saved = *ifd;
            power *= 2;
            sinceSaved = 0;
        }
    }
    if (pages == 0) throw Error(name + ": the header names no page");
    return pages;
}

}  // namespace vri::detail
