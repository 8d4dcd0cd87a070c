#include "libvri/io/vdb_file_extent.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <string>

#include "libvri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kVdbMagic = 0x56444220;    // "VDB " in the first 8 bytes, little endian
constexpr std::uint32_t kBoostUuidVersion = 218;   // the first format with a 36-character UUID
constexpr std::uint32_t kInstancingVersion = 216;  // descriptors name an instance parent from here
constexpr std::uint32_t kUuidChars = 36;

// Thrown by VdbBytes when a read would pass the file's end: where it was, and what was being read.
struct CutShort {
    std::uint64_t at;
    std::string reading;
};

// The file's little-endian integers and length-prefixed strings, read in order; every read is checked
// against the file's length first.
class VdbBytes {
public:
    explicit VdbBytes(const fs::path& path) : in_(path, std::ios::binary), size_(fs::file_size(path)) {
        if (!in_) throw Error(path.string() + ": cannot open");
    }
    std::uint64_t size() const { return size_; }
    std::uint64_t position() const { return position_; }
    std::uint64_t integer(int bytes, const char* reading) {
        require(std::uint64_t(bytes), reading);
        std::array<unsigned char, 8> b{};
        in_.read(reinterpret_cast<char*>(b.data()), bytes);
        std::uint64_t value = 0;
        for (int i = 0; i < bytes; ++i) value |= std::uint64_t(b[static_cast<std::size_t>(i)]) << (8 * i);
        position_ += std::uint64_t(bytes);
        return value;
    }
    void skip(std::uint64_t bytes, const char* reading) {
        require(bytes, reading);
        seek(position_ + bytes);
    }
    void string(const char* reading) { skip(integer(4, reading), reading); }
    void seek(std::uint64_t at) {
        position_ = at;
        in_.seekg(static_cast<std::streamoff>(at));
    }

private:
    void require(std::uint64_t bytes, const char* reading) {
        if (position_ > size_ || size_ - position_ < bytes) throw CutShort{position_ + bytes, reading};
    }
    std::ifstream in_;
    std::uint64_t size_;
    std::uint64_t position_ = 0;
};

}  // namespace

void requireWholeVdbFile(const fs::path& path) {
    VdbBytes file(path);
    try {
        // OpenVDB reads a file shorter than its magic number past its end too, with a different verdict
        // from run to run.
        if (file.size() < 8 || file.integer(8, "the magic number") != kVdbMagic)
            throw Error(path.string() + ": not a VDB file (its first 8 bytes are not OpenVDB's magic number)");
        const std::uint64_t version = file.integer(4, "the header");
        if (version < kBoostUuidVersion) return;
        file.skip(8, "the header");                      // the library's major and minor version
        if (file.integer(1, "the header") == 0) return;  // no grid offsets: nothing says where grids end
        if (version >= 220 && version < 222) file.skip(1, "the header");  // a compression flag of those versions
        file.skip(kUuidChars, "the header");
        const std::uint64_t metadata = file.integer(4, "the file's metadata");
        for (std::uint64_t m = 0; m < metadata; ++m) {
            file.string("the file's metadata");  // name
            file.string("the file's metadata");  // type
            file.string("the file's metadata");  // value, its size first
        }
        const std::uint64_t grids = file.integer(4, "the grid count");
        for (std::uint64_t g = 0; g < grids; ++g) {
            const std::string grid = "grid " + std::to_string(g) + "'s descriptor";
            file.string(grid.c_str());                                     // unique name
            file.string(grid.c_str());                                     // type
            if (version >= kInstancingVersion) file.string(grid.c_str());  // instance parent
            file.skip(16, grid.c_str());                                   // where its metadata and tree start
            const std::uint64_t end = file.integer(8, grid.c_str());
            if (end > file.size())
                throw Error(path.string() + ": cut short: grid " + std::to_string(g) + " ends at byte " +
                            std::to_string(end) + ", beyond the file's end (" + std::to_string(file.size()) +
                            " bytes)");
            if (end < file.position()) return;  // not a layout this walk knows: OpenVDB reads it and says what is wrong
            file.seek(end);
        }
    } catch (const CutShort& cut) {
        throw Error(path.string() + ": cut short: " + cut.reading + " ends at byte " + std::to_string(cut.at) +
                    ", beyond the file's end (" + std::to_string(file.size()) + " bytes)");
    }
}

}  // namespace vri::detail
