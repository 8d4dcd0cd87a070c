#include <doctest/doctest.h>

#include <fstream>

#include "temp_dir.h"
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"

TEST_CASE("file text: a file's bytes, or one error naming what is wrong with the path") {
    vri::test::TempDir dir("file-text");
    const std::string bytes("a\0b\r\nlast", 9);
    std::ofstream(dir / "x.txt", std::ios::binary) << bytes;
    std::ofstream(dir / "empty.txt", std::ios::binary).close();

    CHECK(vri::readFileText(dir / "x.txt", "a text file") == bytes);
    CHECK(vri::tryReadFileText(dir / "empty.txt") == std::string());
    CHECK_FALSE(vri::tryReadFileText(dir / "missing.txt"));
    CHECK_FALSE(vri::tryReadFileText(dir.path));
    CHECK_THROWS_WITH_AS(vri::readFileText(dir / "missing.txt", "a text file"),
                         ((dir / "missing.txt").string() + ": no such file").c_str(), vri::Error);
    CHECK_THROWS_WITH_AS(vri::readFileText(dir.path, "a YAML file"),
                         (dir.path.string() + ": is a directory, expected a YAML file").c_str(), vri::Error);
}

TEST_CASE("file text: at most kTextFileLimit bytes, checked while reading") {
    vri::test::TempDir dir("file-text-limit");
    std::ofstream(dir / "big.txt", std::ios::binary).close();
    std::filesystem::resize_file(dir / "big.txt", vri::kTextFileLimit + 1);  // sparse: no disk written
    std::ofstream(dir / "edge.txt", std::ios::binary).close();
    std::filesystem::resize_file(dir / "edge.txt", vri::kTextFileLimit);

    CHECK(vri::readFileText(dir / "edge.txt", "a text file").size() == vri::kTextFileLimit);
    CHECK_FALSE(vri::tryReadFileText(dir / "big.txt"));
    CHECK_THROWS_WITH_AS(vri::readFileText(dir / "big.txt", "a YAML file"),
                         ((dir / "big.txt").string() + ": more than 67108864 bytes, the limit for a YAML file").c_str(),
                         vri::Error);
    // A device without an end: refused after the limit, and named as what it is.
    CHECK_THROWS_WITH_AS(vri::readFileText("/dev/zero", "a YAML file"),
                         "/dev/zero: not a regular file, more than 67108864 bytes, the limit for a YAML file",
                         vri::Error);
}
