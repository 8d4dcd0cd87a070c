// Text from input shown in one-line messages: control characters escaped, everything else kept.
#include <doctest/doctest.h>

#include <string>

#include "libvri/util/printable.h"

using vri::printable;

TEST_CASE("printable: control characters become \\xNN, other text is unchanged") {
    CHECK(printable("plain text, 1.5 / x") == "plain text, 1.5 / x");
    CHECK(printable("a\nb\rc\td") == "a\\x0ab\\x0dc\\x09d");
    CHECK(printable("\x1b[2Jcleared") == "\\x1b[2Jcleared");
    CHECK(printable(std::string("nul\0byte", 8)) == "nul\\x00byte");
    CHECK(printable("del\x7f") == "del\\x7f");
    // UTF-8 stays, C1 controls (U+0080..U+009F, e.g. CSI U+009B) are escaped by code point.
    CHECK(printable("\xc3\xa9t\xc3\xa9 \xce\xbb") == "\xc3\xa9t\xc3\xa9 \xce\xbb");
    CHECK(printable("\xc2\x9b" "2J") == "\\x9b2J");
    CHECK(printable("\xc2\xa0") == "\xc2\xa0");  // no-break space, printable
    CHECK(printable("\xc2") == "\xc2");           // a lone lead byte at the end is left as it is
    CHECK(printable("") == "");
}

TEST_CASE("printableShort quotes the beginning of long input, cut where a character begins, and says how much more") {
    using vri::printableShort;
    CHECK(printableShort("short") == "short");
    CHECK(printableShort(std::string(300, 'x'), 200) == std::string(200, 'x') + "... (100 more bytes)");
    // "\xc3\xa9" is one character: a cut at byte 3 of "ab\xc3\xa9" moves back to byte 2.
    CHECK(printableShort("ab\xc3\xa9z", 3) == "ab... (3 more bytes)");
    CHECK(printableShort("a\nbcdef", 3) == "a\\x0ab... (4 more bytes)");
}
