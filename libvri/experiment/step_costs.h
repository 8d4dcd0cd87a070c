#pragma once
// What an experiment costs to compute from nothing, read from its last manifest. Every step there
// keeps the wall time of the run that made its outputs (a cached step, the time of the run it
// skipped to), so a manifest written by a fully cached run still prices every step. A planned step
// is priced when the manifest holds a step of the same id with the same arguments, file names taken
// without their folders (data and results may lie elsewhere than when it ran); a new or changed
// step has no price yet, and the estimate counts it instead of guessing.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "libvri/experiment/experiment_plan.h"

namespace vri {

struct CostEstimate {
    double seconds = 0;                    // the priced steps' wall time
    std::map<std::string, double> byKind;  // Step::kind -> seconds: render, diff, command, table, figure
    std::size_t priced = 0, unpriced = 0;  // steps with and without a price
    bool hasManifest = false;
};

// The longest a step's recorded wall time may be to price it: 30 days.
inline constexpr double kMostStepSeconds = 30.0 * 24 * 3600;

// Per step of the plan, its wall time in `manifest` when the manifest holds a step of the same id and
// arguments, and that time is in [0, kMostStepSeconds]; nullopt for the others, and for all when there is
// no such file.
std::vector<std::optional<double>> stepPrices(const Plan& plan, const std::filesystem::path& manifest);

// The plan's steps priced from `manifest` (an experiment's manifest.json). No such file: every step
// unpriced. A manifest that is not one (bad JSON, a missing field) is a vri::Error naming it.
CostEstimate estimateCost(const Plan& plan, const std::filesystem::path& manifest);

// The total wall time of a manifest's steps (the parsed manifest.json): what its experiment cost from
// nothing when it last ran.
double manifestSeconds(const nlohmann::json& manifest);

// "42.1 s", or from two minutes on "47.4 min".
std::string secondsText(double seconds);

}  // namespace vri
