// A TIFF's chain of pages counted from its bytes: classic and BigTIFF, either byte order, and chains that
// end beyond the file, loop, or claim more entries than the file holds.
#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "libvri/io/tiff_page_chain.h"
#include "libvri/util/error.h"
#include "temp_dir.h"

namespace {

// `value` as `bytes` bytes in the given order.
std::string integer(std::uint64_t value, int bytes, bool little) {
    std::string out(static_cast<std::size_t>(bytes), '\0');
    for (int i = 0; i < bytes; ++i) out[static_cast<std::size_t>(little ? i : bytes - 1 - i)] = char(value >> (8 * i));
    return out;
}

// A file of `pages` directories of one (empty) entry each, chained in order from the header; `last` is the
// offset the last one points on to (0: the chain ends).
std::string chain(int pages, bool little, bool big, std::uint64_t last = 0) {
    const int countBytes = big ? 8 : 2, entryBytes = big ? 20 : 12, offsetBytes = big ? 8 : 4;
    const std::uint64_t header = big ? 16 : 8, ifdBytes = std::uint64_t(countBytes + entryBytes + offsetBytes);
    std::string out = std::string(little ? "II" : "MM") + integer(big ? 43 : 42, 2, little);
    if (big) out += integer(8, 2, little) + integer(0, 2, little);
    out += integer(header, offsetBytes, little);
    for (int p = 0; p < pages; ++p) {
        const std::uint64_t next = p + 1 < pages ? header + ifdBytes * std::uint64_t(p + 1) : last;
        out += integer(1, countBytes, little) + std::string(static_cast<std::size_t>(entryBytes), '\0') +
               integer(next, offsetBytes, little);
    }
    return out;
}

int pagesOf(const vri::test::TempDir& dir, const std::string& bytes) {
    std::ofstream(dir / "t.tif", std::ios::binary) << bytes;
    return vri::detail::tiffPageCount(dir / "t.tif");
}

}  // namespace

TEST_CASE("tiff page chain: counts the pages of classic and BigTIFF files in either byte order") {
    const vri::test::TempDir dir("tiff-chain");
    for (const bool little : {true, false})
        for (const bool big : {false, true}) {
            CAPTURE(little);
            CAPTURE(big);
            CHECK(pagesOf(dir, chain(1, little, big)) == 1);
            CHECK(pagesOf(dir, chain(5, little, big)) == 5);
        }
}

TEST_CASE("tiff page chain: a chain cut short, looping or out of the file names the file and the page") {
    const vri::test::TempDir dir("tiff-chain");
    const std::string name = (dir / "t.tif").string();
    const std::string whole = chain(3, true, false);  // directories of 18 bytes at 8, 26 and 44
    CHECK_THROWS_WITH_AS(
        pagesOf(dir, whole.substr(0, whole.size() - 1)),
        (name + ": page 2: its directory at byte 44 (1 entries) ends beyond the file's end (61 bytes)").c_str(),
        vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, whole.substr(0, 44)),
                         (name + ": page 2: its directory at byte 44 lies beyond the file's end (44 bytes)").c_str(),
                         vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, chain(3, false, true, 100000)),
                         doctest::Contains(": page 3: its directory at byte 100000 lies beyond the file's end"),
                         vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, chain(3, true, false, 26)),
                         doctest::Contains("is an earlier page's (the chain of pages loops)"), vri::Error);
    CHECK_THROWS_WITH_AS(
        pagesOf(dir, chain(1, true, false, 8)),
        (name + ": page 1: its directory at byte 8 is an earlier page's (the chain of pages loops)").c_str(),
        vri::Error);
    CHECK_THROWS_WITH_AS(
        pagesOf(dir, std::string("II*\0", 4) + integer(8, 4, true) + integer(65535, 2, true)),
        (name + ": page 0: its directory at byte 8 claims 65535 entries, more than the file's 10 bytes hold").c_str(),
        vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, std::string("II*\0", 4) + integer(0, 4, true)),
                         (name + ": the header names no page").c_str(), vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, "P6\n1 1\n255\n"), doctest::Contains("not a TIFF file"), vri::Error);
    CHECK_THROWS_WITH_AS(pagesOf(dir, "II+\0"), doctest::Contains("expected version 42, or 43 for BigTIFF"),
                         vri::Error);
}
