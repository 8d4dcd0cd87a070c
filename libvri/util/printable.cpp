#include "libvri/util/printable.h"

#include <cctype>

namespace vri {

namespace {

std::string escapeControls(std::string_view text, bool keepNewlines) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    const auto escape = [&](unsigned char c) { out.append({'\\', 'x', kHex[c >> 4], kHex[c & 15]}); };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const bool c1 = c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                        static_cast<unsigned char>(text[i + 1]) <= 0x9f;
        if (c == '\n' && keepNewlines) {
            out.push_back('\n');
        } else if (c < 0x20 || c == 0x7f) {
            escape(c);
        } else if (c1) {
            escape(static_cast<unsigned char>(text[++i]));
        } else {
            out.push_back(text[i]);
        }
    }
    return out;
}

}  // namespace

std::string printable(std::string_view text) { return escapeControls(text, false); }

std::string printableShort(std::string_view text, std::size_t most) {
    if (text.size() <= most) return printable(text);
    std::size_t cut = most;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a character
    return printable(text.substr(0, cut)) + "... (" + std::to_string(text.size() - cut) + " more bytes)";
}

std::string printableLines(std::string_view text) { return escapeControls(text, true); }

std::string oneLine(std::string message) {
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    std::string line;
    for (char ch : message) {
        if (ch == '\n') line += "; ";
        else line += ch;
    }
    return line.empty() ? "unknown error" : line;
}

}  // namespace vri
