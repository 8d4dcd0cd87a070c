#pragma once
// Transfer functions as YAML files, the form experiments/tf/*.yaml and experiment files use.
#include <filesystem>
#include <string>

#include "libvri/core/transfer_function.h"

namespace vri {

// YAML form (see experiments/README.md):
//   emission: color-times-extinction   # or color; optional
//   points:
//     - {s: 0.0, color: [0, 0, 0], tau: 0}
//     - [1.0, 1, 1, 1, 0.5]            # s, r, g, b, tau
// Errors name the file, line and column.
TransferFunction loadTransferFunction(const std::filesystem::path& path);
TransferFunction parseTransferFunction(const std::string& yamlText, const std::string& source);

}  // namespace vri
