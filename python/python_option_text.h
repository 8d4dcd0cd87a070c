#pragma once
// A Python keyword's value as the text a tool's command line would give for the same option, so that
// the module reads its options through the same parsers and checks as the tools (render_option_table.h,
// util/parse.h): 0.25 -> "0.25" (the shortest text that reads back as the same double), (1, 2, 3) ->
// "1,2,3", True -> "true", "exact" -> "exact".
#include <string>

#include <pybind11/pybind11.h>

namespace vri {

// Throws vri::Error "<what>: expected a number, text, or a sequence of numbers, got <type>".
std::string optionText(pybind11::handle value, const std::string& what);

}  // namespace vri
