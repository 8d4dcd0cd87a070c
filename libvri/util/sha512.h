#pragma once
// SHA-512 (FIPS 180-4), the digest the data directory records for each volume
// (SHA512SUMS.txt) and the manifests record for every input file.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace vri {

// Incremental SHA-512: update() with the message in pieces of any size, then hexDigest() once.
class Sha512 {
public:
    Sha512();
    void update(std::span<const std::byte> bytes);
    std::string hexDigest();  // 128 lowercase hex digits; the object is spent afterwards

private:
    void compressBlock(const std::byte* block);

    std::array<std::uint64_t, 8> state_;
    std::array<std::byte, 128> pending_{};  // the start of a block not yet compressed
    std::size_t pendingSize_ = 0;
    std::uint64_t messageBytes_ = 0;
};

std::string sha512Hex(std::span<const std::byte> bytes);

// Reads the file in blocks; throws vri::Error naming the file when it cannot be read.
std::string sha512File(const std::filesystem::path& path);

}  // namespace vri
