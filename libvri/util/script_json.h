#pragma once
// JSON to be placed inside an HTML page's <script> element or a script file: nlohmann's text with every
// '<' written as \u003c, so that no string in it (an id like "</script><script>...") can close the element
// and be read as markup or code, and with U+2028 and U+2029 escaped, which older JavaScript does not accept
// raw inside a string. The text parses as the same JSON (JSON.parse, nlohmann) and as a JavaScript literal.
#include <string>

#include <nlohmann/json.hpp>

namespace vri {

std::string scriptSafeJson(const nlohmann::json& value);

}  // namespace vri
