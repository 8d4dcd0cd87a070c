#include "vri/io/oiio_input.h"

#include <cctype>

#include "vri/util/error.h"

namespace vri::detail {

std::string oneLine(std::string message) {
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    std::string line;
    for (char ch : message) {
        if (ch == '\n') line += "; ";
        else line += ch;
    }
    return line.empty() ? "unknown error" : line;
}

std::unique_ptr<OIIO::ImageInput> openImageInput(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) throw Error(path.string() + ": no such file");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": cannot read image: " + oneLine(OIIO::geterror()));
    return in;
}

}  // namespace vri::detail
