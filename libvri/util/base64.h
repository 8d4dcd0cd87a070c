#pragma once
// Base64 (RFC 4648, the standard alphabet with '=' padding): how binary data rides inside a text file a
// browser reads as a script (the results viewer's float data, viewer_floats.h).
#include <string>
#include <string_view>

namespace vri {

std::string base64Encode(std::string_view bytes);

}  // namespace vri
