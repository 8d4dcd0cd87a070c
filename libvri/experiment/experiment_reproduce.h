#pragma once
// The reproducibility check: numbers an experiment's reproduce: block names, measured on a quick
// run, compared with the ones committed in results/<experiment>/reproduce.json.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"

namespace vri {

// {"<run or comparison id>": {"<metric>": {"R": x, "G": y, "B": z, "A": w}}} from the plan's outputs:
// a run's image (max, mean per channel) or a comparison's diff JSON (max_abs, mean_abs, rmse).
nlohmann::json measureReproduceMetrics(const Experiment& experiment, const Plan& plan);

// One line per number that is missing from `committed` or differs from it by more than its tolerance.
std::vector<std::string> reproduceMismatches(const Experiment& experiment, const nlohmann::json& measured,
                                             const nlohmann::json& committed);

}  // namespace vri
