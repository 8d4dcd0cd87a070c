#pragma once
// The JSON record of the exact reference's statistics, as written in stats files.
#include <nlohmann/json.hpp>

#include "libvri/core/exact_reference.h"

namespace vri {

nlohmann::json toJson(const ExactReferenceStats& stats);  // counts, time, error bound per channel

}  // namespace vri
