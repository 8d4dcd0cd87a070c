#pragma once
// Whether text is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF),
// as JSON must be: nlohmann::json refuses to write anything else, so a file name that is not has to be
// refused before the work whose record would name it.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace vri {

// The index of the first byte that starts no well-formed UTF-8 sequence; nullopt when there is none.
std::optional<std::size_t> firstInvalidUtf8(std::string_view text);

// `text` with every byte of an ill-formed sequence written as \xNN, for a message that names it.
std::string escapeInvalidUtf8(std::string_view text);

}  // namespace vri
