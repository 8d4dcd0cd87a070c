#pragma once
// JSON records of the exact reference's settings and statistics, as written in stats files.
#include <nlohmann/json.hpp>

#include "vri/core/exact_reference.h"

namespace vri {

nlohmann::json toJson(const ExactReferenceOptions& options);  // method "exact", tolerance, tile size
nlohmann::json toJson(const ExactReferenceStats& stats);      // counts, time, error bound per channel

}  // namespace vri
