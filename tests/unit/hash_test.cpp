#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "temp_dir.h"
#include "libvri/util/error.h"
#include "libvri/util/sha512.h"

namespace {

namespace fs = std::filesystem;

std::string sha512Of(std::string_view text) { return vri::sha512Hex(std::as_bytes(std::span(text))); }

// The data directory: $VRI_DATA_DIR, else ../shared/data/volumes beside the repository.
fs::path dataDirectory() {
    const char* env = std::getenv("VRI_DATA_DIR");
    // Lexically: tests/data itself need not exist.
    return env ? fs::path(env) : (fs::path(VRI_TEST_DATA_DIR) / "../../../shared/data/volumes").lexically_normal();
}

}  // namespace

TEST_CASE("sha512: FIPS 180-4 example messages") {
    CHECK(sha512Of("abc") ==
          "ddaf35a193617abacc417349ae20413112e6fa4e89a97ea20a9eeee64b55d39a"
          "2192992a274fc1a836ba3c23a3feebbd454d4423643ce80e2a9ac94fa54ca49f");
    CHECK(sha512Of("") ==
          "cf83e1357eefb8bdf1542850d66d8007d620e4050b5715dc83f4a921d36ce9ce"
          "47d0d13c5d85f2b0ff8318d2877eec2f63b931bd47417a81a538327af927da3e");
    // 896 bits: the padding spills into a second block.
    CHECK(sha512Of("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqr"
                   "lmnopqrsmnopqrstnopqrstu") ==
          "8e959b75dae313da8cf4f72814fc143f8f7779c6eb9f7fa17299aeadb6889018"
          "501d289e4900f7e4331b99dec4b5433ac7d329eeb6dd26545e96e55b874be909");
}

TEST_CASE("sha512: padding edges and a million bytes") {
    // 111 bytes leave room for the marker and length in the last block, 112 do not.
    CHECK(sha512Of(std::string(111, 'a')) ==
          "fa9121c7b32b9e01733d034cfc78cbf67f926c7ed83e82200ef86818196921760"
          "b4beff48404df811b953828274461673c68d04e297b0eb7b2b4d60fc6b566a2");
    CHECK(sha512Of(std::string(112, 'a')) ==
          "c01d080efd492776a1c43bd23dd99d0a2e626d481e16782e75d54c2503b5dc32"
          "bd05f0f1ba33e568b88fd2d970929b719ecbb152f58f130a407c8830604b70ca");
    CHECK(sha512Of(std::string(1000000, 'a')) ==
          "e718483d0ce769644e2e42c7bc15b4638e1f98b13b2044285632a803afa973eb"
          "de0ff244877ea60a4cb0432ce577c31beb009c5c2c49aa2e4eadb217ad8cc09b");
}

TEST_CASE("sha512: pieces of any size hash as the whole message") {
    std::string message;
    for (int i = 0; i < 1000; ++i) message += static_cast<char>(i * 7 + i / 13);
    const std::string whole = sha512Of(message);
    for (std::size_t piece : {1, 5, 111, 127, 128, 129, 300}) {
        vri::Sha512 hash;
        for (std::size_t at = 0; at < message.size(); at += piece)
            hash.update(std::as_bytes(std::span(message).subspan(at, std::min(piece, message.size() - at))));
        CHECK_MESSAGE(hash.hexDigest() == whole, "piece size " << piece);
    }
}

TEST_CASE("sha512: files are hashed in blocks, a missing file is named") {
    vri::test::TempDir dir("hash");
    std::string content(3 * 1024 * 1024 + 17, '\0');  // more than one read buffer
    for (std::size_t i = 0; i < content.size(); ++i) content[i] = static_cast<char>((i * 2654435761u) >> 13);
    std::ofstream(dir / "blob.bin", std::ios::binary) << content;
    CHECK(vri::sha512File(dir / "blob.bin") == sha512Of(content));
    CHECK_THROWS_WITH_AS(vri::sha512File(dir / "missing.raw"), doctest::Contains("missing.raw"), vri::Error);
    CHECK_THROWS_AS(vri::sha512File(dir.path), vri::Error);
}

TEST_CASE("sha512: a data set matches SHA512SUMS.txt, when the data directory is present") {
    const fs::path sums = dataDirectory() / "SHA512SUMS.txt";
    const fs::path fuel = dataDirectory() / "fuel_64x64x64_uint8.raw";
    if (!fs::exists(sums) || !fs::exists(fuel)) return;  // machines without the data sets
    std::ifstream in(sums);
    std::string expected;
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        std::string digest, name;
        if (fields >> digest >> name && name == fuel.filename().string()) expected = digest;
    }
    REQUIRE(!expected.empty());
    CHECK(vri::sha512File(fuel) == expected);
}
