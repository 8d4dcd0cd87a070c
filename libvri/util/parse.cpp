#include "libvri/util/parse.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <type_traits>

#include "libvri/util/error.h"

namespace vri {

namespace {

std::vector<std::string_view> split(std::string_view text, char sep) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= text.size(); ++i)
        if (i == text.size() || text[i] == sep) {
            parts.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    return parts;
}

// The whole text as one number: decimal as std::from_chars reads it, or hexadecimal after "0x" or "0X"
// (a float such as 0x1p-3, exact in binary, or an integer such as 0x10), with an optional minus before
// it. Hexadecimal is how a float is written exactly, so every option and field takes it.
template <class T>
bool parseNumber(std::string_view s, T& value) {
    const bool negative = !s.empty() && s.front() == '-';
    std::string_view digits = s.substr(negative ? 1 : 0);
    if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
        digits.remove_prefix(2);
        if (digits.front() == '-') return false;  // from_chars would read a second sign
        const char* end = digits.data() + digits.size();
        std::from_chars_result r;
        if constexpr (std::is_floating_point_v<T>)
            r = std::from_chars(digits.data(), end, value, std::chars_format::hex);
        else
            r = std::from_chars(digits.data(), end, value, 16);
        if (r.ec != std::errc() || r.ptr != end) return false;
        if (negative) value = -value;
        return true;
    }
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size();
}

// Exactly N finite numbers separated by commas; throws vri::Error(message) otherwise.
template <int N>
glm::vec<N, double> finiteVector(const std::string& text, const std::string& message) {
    const auto parts = split(text, ',');
    glm::vec<N, double> v;
    bool ok = parts.size() == N;
    for (int i = 0; ok && i < N; ++i) ok = parseNumber(parts[i], v[i]) && std::isfinite(v[i]);
    if (!ok) throw Error(message);
    return v;
}

}  // namespace

std::optional<std::int64_t> integerFromText(std::string_view text, bool* outOfRange) {
    std::int64_t value;
    const bool ok = parseNumber(text, value);
    if (outOfRange) {
        std::string_view digits = text.substr(!text.empty() && text.front() == '-' ? 1 : 0);
        const bool hex = digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X');
        if (hex) digits.remove_prefix(2);
        const auto digit = [hex](unsigned char c) { return hex ? std::isxdigit(c) != 0 : std::isdigit(c) != 0; };
        *outOfRange = !ok && !digits.empty() && std::all_of(digits.begin(), digits.end(), digit);
    }
    return ok ? std::optional<std::int64_t>(value) : std::nullopt;
}

std::optional<double> numberFromText(std::string_view text) {
    double value;
    return parseNumber(text, value) ? std::optional<double>(value) : std::nullopt;
}

glm::dvec2 parseVec2(const std::string& text, const std::string& what) {
    return finiteVector<2>(text, what + ": expected two numbers x,y, got '" + text + "'");
}

glm::dvec3 parseVec3(const std::string& text, const std::string& what) {
    return finiteVector<3>(text, what + ": expected three numbers x,y,z, got '" + text + "'");
}

namespace {

// "a,b,c" -> three integers in [least, 1e9]; throws "<what>: expected <expected>, got '<text>'" otherwise.
glm::ivec3 parseIntegerTriple(const std::string& text, const std::string& what, int least, const char* expected) {
    const auto parts = split(text, ',');
    glm::ivec3 v;
    bool ok = parts.size() == 3;
    for (int i = 0; ok && i < 3; ++i) ok = parseNumber(parts[i], v[i]) && v[i] >= least && v[i] <= 1000000000;
    if (!ok) throw Error(what + ": expected " + expected + ", got '" + text + "'");
    return v;
}

}  // namespace

glm::ivec3 parseDims(const std::string& text, const std::string& what) {
    return parseIntegerTriple(text, what, 1, "three positive integers X,Y,Z");
}

glm::ivec3 parseIndex3(const std::string& text, const std::string& what) {
    return parseIntegerTriple(text, what, 0, "three whole numbers I,J,K from 0");
}

glm::dvec2 parseRange(const std::string& text, const std::string& what) {
    const auto parts = split(text, ',');
    glm::dvec2 v;
    bool ok = parts.size() == 2 && parseNumber(parts[0], v.x) && parseNumber(parts[1], v.y) &&
              std::isfinite(v.x) && std::isfinite(v.y) && v.y > v.x;
    if (!ok) throw Error(what + ": expected lo,hi with hi > lo, got '" + text + "'");
    // Values map to (v - lo) / (hi - lo): a width past the largest double maps every value to 0.
    if (!std::isfinite(v.y - v.x))
        throw Error(what + ": hi - lo must be at most the largest double (about 1.8e308), got '" + text + "'");
    return v;
}

glm::ivec2 parseSize(const std::string& text, const std::string& what) {
    const auto parts = split(text, 'x');
    // Decimal sides only: 'x' separates them, so a hexadecimal side (0X10x8) would read one way and not another.
    const auto decimal = [](std::string_view side) {
        return !side.empty() && side.find_first_not_of("0123456789") == std::string_view::npos;
    };
    const bool sides = parts.size() == 2 && decimal(parts[0]) && decimal(parts[1]);
    glm::ivec2 v;
    bool ok = sides && parseNumber(parts[0], v.x) && parseNumber(parts[1], v.y);
    if (!ok) {  // a whole number past int's range is too large, not malformed
        std::int64_t wide[2];
        if (sides && parseNumber(parts[0], wide[0]) && parseNumber(parts[1], wide[1]) && wide[0] > 0 && wide[1] > 0)
            throw Error(what + ": an image side is at most 2147483647 pixels, got '" + text + "'");
    }
    if (!ok || v.x <= 0 || v.y <= 0)
        throw Error(what + ": expected a positive image size WIDTHxHEIGHT, got '" + text + "'");
    return v;
}

glm::ivec2 parsePixel(const std::string& text, const std::string& what) {
    const auto parts = split(text, ',');
    glm::ivec2 v;
    bool ok = parts.size() == 2 && parseNumber(parts[0], v.x) && parseNumber(parts[1], v.y);
    if (!ok || v.x < 0 || v.y < 0) throw Error(what + ": expected a pixel X,Y (integers >= 0), got '" + text + "'");
    return v;
}

glm::ivec4 parseRegion(const std::string& text, const std::string& what) {
    const auto parts = split(text, ',');
    glm::ivec4 v;
    bool ok = parts.size() == 4;
    for (int i = 0; ok && i < 4; ++i) ok = parseNumber(parts[i], v[i]);
    ok = ok && v.x >= 0 && v.y >= 0 && v.z >= 1 && v.w >= 1 &&
         std::int64_t(v.x) + v.z <= std::numeric_limits<int>::max() &&
         std::int64_t(v.y) + v.w <= std::numeric_limits<int>::max();
    if (!ok)
        throw UsageError(what + ": expected a pixel rectangle X,Y,WIDTH,HEIGHT (integers, X and Y >= 0, WIDTH and "
                                "HEIGHT >= 1, X + WIDTH and Y + HEIGHT below 2^31), got '" + text + "'");
    return v;
}

double parsePositive(const std::string& text, const std::string& what) {
    double v;
    if (!parseNumber(text, v) || !std::isfinite(v) || !(v > 0.0))
        throw Error(what + ": expected a number > 0, got '" + text + "'");
    return v;
}

double parseNonNegative(const std::string& text, const std::string& what) {
    double v;
    if (!parseNumber(text, v) || !std::isfinite(v) || !(v >= 0.0))
        throw Error(what + ": expected a number >= 0, got '" + text + "'");
    return v;
}

int parseCount(const std::string& text, const std::string& what, int least) {
    int v;
    if (!parseNumber(text, v) || v < least)
        throw Error(what + ": expected a whole number >= " + std::to_string(least) + ", got '" + text + "'");
    return v;
}

int parseCount(const std::string& text, const std::string& what, int least, int most) {
    int v;
    if (!parseNumber(text, v) || v < least || v > most)
        throw Error(what + ": expected a whole number from " + std::to_string(least) + " to " + std::to_string(most) +
                    ", got '" + text + "'");
    return v;
}

double parseLimit(const std::string& text, const std::string& what) {
    if (text == "none") return std::numeric_limits<double>::infinity();
    double v;
    if (!parseNumber(text, v) || !std::isfinite(v) || !(v > 0.0))
        throw Error(what + ": expected a positive number or 'none', got '" + text + "'");
    return v;
}

std::vector<std::string> parseWordList(const std::string& text, const std::string& what) {
    std::vector<std::string> words;
    for (std::string_view part : split(text, ',')) {
        if (part.empty())
            throw Error(what + ": an empty item in '" + text + "'; expected items separated by single ','");
        words.emplace_back(part);
    }
    return words;
}

std::vector<double> parsePositiveList(const std::string& text, const std::string& what) {
    std::vector<double> values;
    for (std::string_view part : split(text, ',')) {
        double v = 0.0;
        if (!parseNumber(part, v) || !std::isfinite(v) || !(v > 0.0))
            throw Error(what + ": expected positive numbers separated by commas, got '" + text + "'");
        values.push_back(v);
    }
    return values;
}

std::vector<int> parseIndexList(const std::string& text, const std::string& what, int count) {
    std::vector<int> values;
    for (std::string_view part : split(text, ',')) {
        int v = -1;
        if (!parseNumber(part, v) || v < 0 || v >= count)
            throw Error(what + ": expected indices in 0.." + std::to_string(count - 1) + " separated by commas, got '" +
                        text + "'");
        values.push_back(v);
    }
    return values;
}

}  // namespace vri
