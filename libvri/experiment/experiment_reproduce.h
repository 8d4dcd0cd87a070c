#pragma once
// The reproducibility check: numbers an experiment's reproduce: block names, measured on a quick
// run, compared with the ones committed in results/<experiment>/reproduce.json.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"

namespace vri {

// {"<run or comparison id>": {"<metric>": {"R": x, "G": y, "B": z, "A": w}}} from the plan's outputs:
// a run's image (max, mean per channel) or a comparison's diff JSON (max_abs, mean_abs, rmse).
nlohmann::json measureReproduceMetrics(const Experiment& experiment, const Plan& plan);

// The part of a plan that a check of its reproduce: numbers needs: the steps the block names (a run's, a
// comparison's or a command's), those writing a file of `readElsewhere` (another experiment of the same run
// reads it), and every step they depend on, in plan order. A plan whose experiment names no numbers is
// returned whole. The quick runs of make test's reproducibility check are several times shorter for it
// (paper-b-cpu's checks read 7 of its 295 steps).
Plan checkedPart(const Experiment& experiment, const Plan& plan, const std::set<std::filesystem::path>& readElsewhere);

// One line per number that is missing from `committed` or differs from it by more than its tolerance.
std::vector<std::string> reproduceMismatches(const Experiment& experiment, const nlohmann::json& measured,
                                             const nlohmann::json& committed);

}  // namespace vri
