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
