#pragma once
// Numbers as text that reads back exactly: data files, headers and messages share one form.
#include <string>

namespace vri {

// The shortest text that reads back as the same double ("0.1", "1e-09", "inf", "-inf", "nan").
std::string exactNumber(double value);

}  // namespace vri
