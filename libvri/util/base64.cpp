#include "libvri/util/base64.h"

#include <cstdint>

#include "libvri/util/checked_size.h"

namespace vri {

std::string base64Encode(std::string_view bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    // Every 3 bytes become 4 characters, a last partial group padded to 4.
    std::string text(checkedBytes("base64 text", {bytes.size() / 3 + (bytes.size() % 3 != 0), 4}), '=');
    std::size_t out = 0;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = bytes.size() - i < 3 ? bytes.size() - i : 3;
        std::uint32_t group = 0;
        for (std::size_t k = 0; k < 3; ++k)
            group = group << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k <= n; ++k) text[out + k] = kAlphabet[group >> (18 - 6 * k) & 63];
        out += 4;
    }
    return text;
}

}  // namespace vri
