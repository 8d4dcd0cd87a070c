#pragma once
// Text from input files and arguments, made safe to show in a one-line message: a control character
// (a newline, an escape sequence's ESC, a C1 control) would split the line or drive the terminal.
#include <string>
#include <string_view>

namespace vri {

// `text` with every C0 control character, DEL and UTF-8-encoded C1 control written as \xNN (the C1
// controls as their code point, \x80..\x9f); everything else, other UTF-8 included, unchanged.
std::string printable(std::string_view text);

// printable() of at most the first `most` bytes of `text` (cut where a UTF-8 character begins), then
// "... (N more bytes)" when it was longer: input quoted in a message (a 50 MB squeue line) stays a line.
std::string printableShort(std::string_view text, std::size_t most = 200);

// The longest one-line message a tool prints; a longer one is cut as printableShort cuts.
inline constexpr std::size_t kMaxMessageBytes = 2000;

// The same, newlines kept: text of several lines (a DetailedError's) shown as those lines.
std::string printableLines(std::string_view text);

// A library's message (OpenImageIO's, OpenEXR's) as one line: trailing white space dropped, each newline
// written as "; ", "unknown error" for an empty one.
std::string oneLine(std::string message);

}  // namespace vri
