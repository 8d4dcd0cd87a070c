// The last-resort messages of guardedMain: library exceptions said in words, naming the path.
#include <doctest/doctest.h>

#include <filesystem>
#include <new>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "common/cli.h"
#include "libvri/util/json_file.h"

TEST_CASE("unexpected errors: bad_alloc, file-system and JSON failures in words") {
    CHECK(vri::describeUnexpected(std::bad_alloc()).starts_with("out of memory:"));
    const std::filesystem::filesystem_error fs("directory iterator cannot open directory", "missing/dir",
                                               std::make_error_code(std::errc::no_such_file_or_directory));
    CHECK(vri::describeUnexpected(fs) == "missing/dir: No such file or directory");
    try {
        (void)nlohmann::json::parse("{\"a\": 1}").at("b");
        FAIL("expected a JSON exception");
    } catch (const nlohmann::json::exception& e) {
        CHECK(vri::jsonExceptionText(e) == "key 'b' not found");
        CHECK(vri::describeUnexpected(e) == "JSON: key 'b' not found");
    }
    try {
        (void)nlohmann::json(std::string("a\xff")).dump();
        FAIL("expected a JSON exception");
    } catch (const nlohmann::json::exception& e) {
        CHECK(vri::describeUnexpected(e) ==
              "a file name or text to be written as JSON is not valid UTF-8 (invalid UTF-8 byte at index 1: 0xFF)");
    }
    const std::runtime_error other("something else");
    CHECK(vri::describeUnexpected(other) == "something else");
}
