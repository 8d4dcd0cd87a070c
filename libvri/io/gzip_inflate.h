#pragma once
// Private to the volume readers: voxel data compressed with zlib's deflate, as NRRD's "encoding: gzip"
// and MetaImage's "CompressedData = True" store them.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vri::detail {

// The `expectedBytes` bytes that the gzip or zlib stream starting `offset` bytes into `path` inflates to
// (the caller has checked expectedBytes against the byte limit and the stream's size). The buffer grows
// as the stream yields bytes, so that a header claiming more than the stream holds costs what the stream
// holds, not what the header claims. Throws vri::Error "<where>: ..." when the stream is corrupt, ends
// early, or holds more than expectedBytes.
std::vector<std::byte> inflateFile(const std::filesystem::path& path, std::uintmax_t offset,
                                   std::size_t expectedBytes, const std::string& where);

}  // namespace vri::detail
