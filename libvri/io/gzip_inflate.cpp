#include "libvri/io/gzip_inflate.h"

#include <fstream>

#include <zlib.h>

#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// inflateEnd on every path out, thrown or not.
struct InflateStream {
    z_stream z{};
    InflateStream(const std::string& where) {
        // 15 + 32: the largest window, and a gzip or a zlib header recognised by its first bytes.
        if (inflateInit2(&z, 15 + 32) != Z_OK) throw Error(where + ": cannot start zlib");
    }
    ~InflateStream() { inflateEnd(&z); }
    InflateStream(const InflateStream&) = delete;
    InflateStream& operator=(const InflateStream&) = delete;
};

}  // namespace

std::vector<std::byte> inflateFile(const fs::path& path, std::uintmax_t offset, std::size_t expectedBytes,
                                   const std::string& where) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(where + ": cannot open " + path.string());
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in) throw Error(where + ": cannot seek to byte " + std::to_string(offset) + " of " + path.string());

    // Reserved, not resized: the untouched pages of the reservation take no memory; each step below
    // grows the buffer by what inflate may write next.
    std::vector<std::byte> out;
    allocateOrExplain(where, expectedBytes, [&] { out.reserve(expectedBytes); });
    InflateStream stream(where);
    z_stream& z = stream.z;
    // One byte more than expected of room: a stream that fills it holds too much.
    unsigned char spare = 0;
    std::vector<char> chunk(1 << 16);
    constexpr std::size_t kStep = std::size_t(1) << 22;
    int status = Z_OK;
    while (status != Z_STREAM_END) {
        if (z.avail_in == 0) {
            in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
            const std::streamsize got = in.gcount();
            if (got == 0)
                throw Error(where + ": the compressed data end after " + std::to_string(out.size()) +
                            " bytes, expected " + std::to_string(expectedBytes));
            z.next_in = reinterpret_cast<Bytef*>(chunk.data());
            z.avail_in = static_cast<uInt>(got);
        }
        const std::size_t produced = out.size();
        const bool inSpare = produced >= expectedBytes;
        const std::size_t room = inSpare ? 1 : std::min(expectedBytes - produced, kStep);
        if (!inSpare) out.resize(produced + room);
        z.next_out = inSpare ? &spare : reinterpret_cast<Bytef*>(out.data() + produced);
        z.avail_out = static_cast<uInt>(room);
        status = inflate(&z, Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR)
            throw Error(where + ": not a valid gzip/zlib stream (" + (z.msg ? z.msg : "zlib error " + std::to_string(status)) + ")");
        if (inSpare && z.avail_out == 0)
            throw Error(where + ": the compressed data hold more than the expected " + std::to_string(expectedBytes) +
                        " bytes");
        if (!inSpare) out.resize(produced + room - z.avail_out);
    }
    const std::size_t produced = out.size();
    if (produced != expectedBytes)
        throw Error(where + ": the compressed data hold " + std::to_string(produced) + " bytes, expected " +
                    std::to_string(expectedBytes));
    return out;
}

}  // namespace vri::detail
