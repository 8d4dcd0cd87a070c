#pragma once
// Text to values, as command-line options and experiment files spell them: the parse* functions throw
// vri::Error naming `what` (an option or a field) and quoting the text when it is not what is expected;
// integerFromText and numberFromText, the forms they all read, return nullopt instead.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace vri {

// "x,y" -> vector; throws vri::Error naming `what` unless there are exactly two finite numbers.
glm::dvec2 parseVec2(const std::string& text, const std::string& what);
// "x,y,z" -> vector; throws vri::Error naming `what` unless there are exactly three finite numbers.
glm::dvec3 parseVec3(const std::string& text, const std::string& what);
// "x,y,z" -> integer dims; throws vri::Error naming `what` unless all three are integers in [1, 1e9].
glm::ivec3 parseDims(const std::string& text, const std::string& what);
// "i,j,k" -> three integers in [0, 1e9]; throws vri::Error naming `what` otherwise.
glm::ivec3 parseIndex3(const std::string& text, const std::string& what);
// "lo,hi" -> pair; throws vri::Error naming `what` unless both are finite, hi > lo and hi - lo is finite.
glm::dvec2 parseRange(const std::string& text, const std::string& what);
// "WxH" -> (W, H); throws vri::Error naming `what` unless both are positive decimal integers.
glm::ivec2 parseSize(const std::string& text, const std::string& what);
// "X,Y" -> a pixel; throws vri::Error naming `what` unless both are integers >= 0.
glm::ivec2 parsePixel(const std::string& text, const std::string& what);
// "X,Y,W,H" -> a rectangle of pixels (x, y, width, height): four integers, X and Y >= 0, W and H >= 1,
// X + W and Y + H within an int. A command line spells it, so what is not that is a vri::UsageError.
glm::ivec4 parseRegion(const std::string& text, const std::string& what);
// A finite number > 0 (parsePositive) or >= 0 (parseNonNegative); throws vri::Error
// "<what>: expected a number > 0, got '<text>'" otherwise.
double parsePositive(const std::string& text, const std::string& what);
double parseNonNegative(const std::string& text, const std::string& what);
// A whole number >= `least`; throws vri::Error "<what>: expected a whole number >= <least>, got '<text>'" otherwise.
int parseCount(const std::string& text, const std::string& what, int least);
// A whole number in [least, most]; throws vri::Error "<what>: expected a whole number from <least> to <most>, got
// '<text>'" otherwise.
int parseCount(const std::string& text, const std::string& what, int least, int most);
// A positive finite number, or "none" -> +infinity (no limit); throws vri::Error naming `what` otherwise.
double parseLimit(const std::string& text, const std::string& what);

// The whole text as one integer: decimal, or hexadecimal after 0x or 0X, with an optional minus (no plus, no
// spaces, a leading 0 not octal), as every function here reads integers; nullopt for any other text. Where
// `outOfRange` is given it tells text of that form whose value does not fit in 64 bits.
std::optional<std::int64_t> integerFromText(std::string_view text, bool* outOfRange = nullptr);
// The whole text as one number: decimal as std::from_chars reads it (inf and nan included: the reader of the
// value says what range it takes), or a hexadecimal float after 0x (0x1p-3); nullopt otherwise.
std::optional<double> numberFromText(std::string_view text);

// "a,b,c" -> the words between the commas; throws vri::Error "<what>: an empty item in '<text>'; expected items
// separated by single ','" for an empty one (a,,b, a trailing comma, an empty text).
std::vector<std::string> parseWordList(const std::string& text, const std::string& what);
// "1,4,16" -> positive finite numbers; throws vri::Error naming `what` otherwise.
std::vector<double> parsePositiveList(const std::string& text, const std::string& what);
// "3,17" -> integers in [0, count); throws vri::Error naming `what` otherwise.
std::vector<int> parseIndexList(const std::string& text, const std::string& what, int count);

}  // namespace vri
