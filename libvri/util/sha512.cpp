#include "libvri/util/sha512.h"

#include <cstring>
#include <fstream>
#include <vector>

#include "libvri/util/error.h"

namespace vri {

namespace {

// FIPS 180-4, 5.3.5: the first 64 bits of the fractional parts of the square roots of the first
// eight primes, floor(sqrt(p) * 2^64) mod 2^64.
constexpr std::array<std::uint64_t, 8> kInitialState{
    0x6a09e667f3bcc908, 0xbb67ae8584caa73b, 0x3c6ef372fe94f82b, 0xa54ff53a5f1d36f1,
    0x510e527fade682d1, 0x9b05688c2b3e6c1f, 0x1f83d9abfb41bd6b, 0x5be0cd19137e2179};

// FIPS 180-4, 4.2.3: the same for the cube roots of the first eighty primes.
constexpr std::array<std::uint64_t, 80> kRoundConstants{
    0x428a2f98d728ae22, 0x7137449123ef65cd, 0xb5c0fbcfec4d3b2f, 0xe9b5dba58189dbbc,
    0x3956c25bf348b538, 0x59f111f1b605d019, 0x923f82a4af194f9b, 0xab1c5ed5da6d8118,
    0xd807aa98a3030242, 0x12835b0145706fbe, 0x243185be4ee4b28c, 0x550c7dc3d5ffb4e2,
    0x72be5d74f27b896f, 0x80deb1fe3b1696b1, 0x9bdc06a725c71235, 0xc19bf174cf692694,
    0xe49b69c19ef14ad2, 0xefbe4786384f25e3, 0x0fc19dc68b8cd5b5, 0x240ca1cc77ac9c65,
    0x2de92c6f592b0275, 0x4a7484aa6ea6e483, 0x5cb0a9dcbd41fbd4, 0x76f988da831153b5,
    0x983e5152ee66dfab, 0xa831c66d2db43210, 0xb00327c898fb213f, 0xbf597fc7beef0ee4,
    0xc6e00bf33da88fc2, 0xd5a79147930aa725, 0x06ca6351e003826f, 0x142929670a0e6e70,
    0x27b70a8546d22ffc, 0x2e1b21385c26c926, 0x4d2c6dfc5ac42aed, 0x53380d139d95b3df,
    0x650a73548baf63de, 0x766a0abb3c77b2a8, 0x81c2c92e47edaee6, 0x92722c851482353b,
    0xa2bfe8a14cf10364, 0xa81a664bbc423001, 0xc24b8b70d0f89791, 0xc76c51a30654be30,
    0xd192e819d6ef5218, 0xd69906245565a910, 0xf40e35855771202a, 0x106aa07032bbd1b8,
    0x19a4c116b8d2d0c8, 0x1e376c085141ab53, 0x2748774cdf8eeb99, 0x34b0bcb5e19b48a8,
    0x391c0cb3c5c95a63, 0x4ed8aa4ae3418acb, 0x5b9cca4f7763e373, 0x682e6ff3d6b2b8a3,
    0x748f82ee5defb2fc, 0x78a5636f43172f60, 0x84c87814a1f0ab72, 0x8cc702081a6439ec,
    0x90befffa23631e28, 0xa4506cebde82bde9, 0xbef9a3f7b2c67915, 0xc67178f2e372532b,
    0xca273eceea26619c, 0xd186b8c721c0c207, 0xeada7dd6cde0eb1e, 0xf57d4f7fee6ed178,
    0x06f067aa72176fba, 0x0a637dc5a2c898a6, 0x113f9804bef90dae, 0x1b710b35131c471b,
    0x28db77f523047d84, 0x32caab7b40c72493, 0x3c9ebe0a15c9bebc, 0x431d67c49c100d4c,
    0x4cc5d4becb3e42b6, 0x597f299cfc657e2a, 0x5fcb6fab3ad6faec, 0x6c44198c4a475817};

constexpr std::size_t kBlockBytes = 128;

constexpr std::uint64_t rotateRight(std::uint64_t x, int n) { return (x >> n) | (x << (64 - n)); }

// The message is read as big-endian 64-bit words whatever the machine's byte order.
std::uint64_t loadBigEndian(const std::byte* p) {
    std::uint64_t word = 0;
    for (int i = 0; i < 8; ++i) word = (word << 8) | std::to_integer<std::uint64_t>(p[i]);
    return word;
}

void storeBigEndian(std::uint64_t word, std::byte* p) {
    for (int i = 7; i >= 0; --i, word >>= 8) p[i] = static_cast<std::byte>(word & 0xff);
}

}  // namespace

Sha512::Sha512() : state_(kInitialState) {}

void Sha512::compressBlock(const std::byte* block) {
    std::array<std::uint64_t, 80> schedule;
    for (int t = 0; t < 16; ++t) schedule[t] = loadBigEndian(block + 8 * t);
    for (int t = 16; t < 80; ++t) {
        const std::uint64_t w15 = schedule[t - 15], w2 = schedule[t - 2];
        const std::uint64_t sigma0 = rotateRight(w15, 1) ^ rotateRight(w15, 8) ^ (w15 >> 7);
        const std::uint64_t sigma1 = rotateRight(w2, 19) ^ rotateRight(w2, 61) ^ (w2 >> 6);
        schedule[t] = sigma1 + schedule[t - 7] + sigma0 + schedule[t - 16];
    }
    auto [a, b, c, d, e, f, g, h] = state_;
    for (int t = 0; t < 80; ++t) {
        const std::uint64_t sum1 = rotateRight(e, 14) ^ rotateRight(e, 18) ^ rotateRight(e, 41);
        const std::uint64_t choose = (e & f) ^ (~e & g);
        const std::uint64_t temp1 = h + sum1 + choose + kRoundConstants[t] + schedule[t];
        const std::uint64_t sum0 = rotateRight(a, 28) ^ rotateRight(a, 34) ^ rotateRight(a, 39);
        const std::uint64_t majority = (a & b) ^ (a & c) ^ (b & c);
        const std::uint64_t temp2 = sum0 + majority;
        h = g;
        g = f;
        f = e;
        e = d + temp1;
        d = c;
        c = b;
        b = a;
        a = temp1 + temp2;
    }
    const std::array<std::uint64_t, 8> working{a, b, c, d, e, f, g, h};
    for (int i = 0; i < 8; ++i) state_[i] += working[i];
}

void Sha512::update(std::span<const std::byte> bytes) {
    messageBytes_ += bytes.size();
    if (pendingSize_ > 0) {
        const std::size_t take = std::min(kBlockBytes - pendingSize_, bytes.size());
        std::memcpy(pending_.data() + pendingSize_, bytes.data(), take);
        pendingSize_ += take;
        bytes = bytes.subspan(take);
        if (pendingSize_ < kBlockBytes) return;
        compressBlock(pending_.data());
        pendingSize_ = 0;
    }
    for (; bytes.size() >= kBlockBytes; bytes = bytes.subspan(kBlockBytes)) compressBlock(bytes.data());
    std::memcpy(pending_.data(), bytes.data(), bytes.size());
    pendingSize_ = bytes.size();
}

std::string Sha512::hexDigest() {
    // Padding (FIPS 180-4, 5.1.2): a one bit, zeros up to 112 mod 128 bytes, then the message
    // length in bits as a 128-bit big-endian number.
    const std::uint64_t lengthHigh = messageBytes_ >> 61, lengthLow = messageBytes_ << 3;
    std::array<std::byte, kBlockBytes + 16> padding{};
    padding[0] = std::byte{0x80};
    const std::size_t zerosAndMarker = (pendingSize_ < 112 ? 112 : 240) - pendingSize_;
    storeBigEndian(lengthHigh, padding.data() + zerosAndMarker);
    storeBigEndian(lengthLow, padding.data() + zerosAndMarker + 8);
    update(std::span(padding.data(), zerosAndMarker + 16));

    static constexpr char kHexDigits[] = "0123456789abcdef";
    std::string hex;
    for (std::uint64_t word : state_)
        for (int shift = 60; shift >= 0; shift -= 4) hex += kHexDigits[(word >> shift) & 0xf];
    return hex;
}

std::string sha512Hex(std::span<const std::byte> bytes) {
    Sha512 hash;
    hash.update(bytes);
    return hash.hexDigest();
}

std::string sha512File(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(path.string() + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw Error(path.string() + ": is a directory, cannot hash it");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open for hashing");
    Sha512 hash;
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        hash.update(std::as_bytes(std::span(buffer.data(), static_cast<std::size_t>(in.gcount()))));
    }
    if (in.bad()) throw Error(path.string() + ": read error while hashing");
    return hash.hexDigest();
}

}  // namespace vri
