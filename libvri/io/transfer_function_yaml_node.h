#pragma once
// Private: builds a transfer function from an already parsed YAML node, so that experiment files
// can embed one and still report positions in their own file.
#include <string>

#include <yaml-cpp/yaml.h>

#include "libvri/core/transfer_function.h"

namespace vri {

TransferFunction transferFunctionFromYaml(const YAML::Node& root, const std::string& source);

}  // namespace vri
