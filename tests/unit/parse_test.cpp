// Text to values (parse.h): decimal and hexadecimal numbers, as every option and field reads them.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "libvri/util/error.h"
#include "libvri/util/parse.h"

using namespace vri;

TEST_CASE("parse: numbers in decimal or hexadecimal, the whole text and nothing else") {
    CHECK(parsePositive("0.125", "--step") == 0.125);
    CHECK(parsePositive("0x1p-3", "--step") == 0.125);  // exact in binary
    CHECK(parsePositive("0X1.8P1", "--step") == 3.0);
    CHECK(parseNonNegative("0x0p0", "--tolerance") == 0.0);
    CHECK(parseCount("0x10", "--repeat", 1) == 16);
    CHECK(parseCount("16", "--repeat", 1) == 16);
    CHECK(parseVec3("-0x1p1,0x10,1.5", "--eye") == glm::dvec3(-2.0, 16.0, 1.5));
    for (const char* text : {"0x10x8", "0X10x8", "8x0X10", "-8x8", "8x-8", "08x8 ", "8x"}) {  // x separates the sides
        CAPTURE(text);
        CHECK_THROWS_AS(parseSize(text, "--size"), Error);
    }
    CHECK(parseSize("0800x600", "--size") == glm::ivec2(800, 600));  // decimal, a leading 0 not octal
    CHECK(parseWordList("a,b", "--only") == std::vector<std::string>{"a", "b"});
    for (const char* text : {"", "a,", ",a", "a,,b"}) {
        CAPTURE(text);
        CHECK_THROWS_WITH_AS(parseWordList(text, "--only"),
                             ("--only: an empty item in '" + std::string(text) + "'; expected items separated by single ','").c_str(),
                             Error);
    }
    for (const char* text : {"0x", "0x-1", "0x+1", "-0x-1", "0xg", "0x1p", "0x1p-3 ", " 0x1", "--0x1", "0x1q", "1e999"}) {
        CAPTURE(text);
        CHECK_THROWS_AS(parsePositive(text, "--step"), Error);
    }
    CHECK_THROWS_WITH_AS(parsePositive("-0x1p-3", "--step"), "--step: expected a number > 0, got '-0x1p-3'", Error);
    CHECK_THROWS_AS(parseCount("0x1.8p1", "--repeat", 1), Error);  // not a whole number
    CHECK_THROWS_AS(parseCount("0x100000000", "--repeat", 1), Error);  // past int
}

TEST_CASE("parse: one integer or one number from text, and integers past 64 bits told apart") {
    bool outOfRange = true;
    CHECK(integerFromText("010", &outOfRange) == 10);  // a leading 0 is not octal
    CHECK_FALSE(outOfRange);
    CHECK(integerFromText("08") == 8);
    CHECK(integerFromText("-0x10") == -16);
    CHECK(integerFromText("9223372036854775807") == std::numeric_limits<std::int64_t>::max());
    for (const char* text : {"", " 1", "1 ", "+1", "1e3", "1.0", "0x", "0x-1", "--1", "٣"}) {
        CAPTURE(text);
        CHECK_FALSE(integerFromText(text, &outOfRange));
        CHECK_FALSE(outOfRange);
    }
    for (const char* text : {"9223372036854775808", "-99999999999999999999", "0x10000000000000000"}) {
        CAPTURE(text);
        CHECK_FALSE(integerFromText(text, &outOfRange));
        CHECK(outOfRange);
    }
    CHECK(numberFromText("0x1p-3") == 0.125);
    CHECK(numberFromText("-2.5e1") == -25.0);
    CHECK(numberFromText("-inf") == -std::numeric_limits<double>::infinity());  // the option's reader refuses it
    CHECK(std::isnan(numberFromText("nan").value()));
    for (const char* text : {"", " 1", "1 ", "+1", "1e999", "1,5", "0x1q"}) {
        CAPTURE(text);
        CHECK_FALSE(numberFromText(text));
    }
}
