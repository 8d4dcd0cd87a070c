// Pricing an experiment's steps from the wall times its last manifest recorded.
#include "libvri/experiment/step_costs.h"

#include <cstdio>
#include <map>

#include "libvri/util/json_file.h"

namespace vri {

namespace fs = std::filesystem;

std::vector<std::optional<double>> stepPrices(const Plan& plan, const fs::path& manifest) {
    // id -> {command, seconds} of the last run
    std::map<std::string, std::pair<std::string, double>> last;
    if (fs::is_regular_file(manifest)) {
        const nlohmann::json m = readJsonFile(manifest);
        readingJsonOf(manifest, [&] {
            for (const nlohmann::json& s : m.at("steps"))
                last[s.at("id").get<std::string>()] = {s.at("command").get<std::string>(),
                                                       s.at("wall_seconds").get<double>()};
        });
    }
    std::vector<std::optional<double>> prices;
    for (const Step& step : plan.steps) {
        // The manifest's command starts with the tool as the run that wrote it named it (its build
        // folder); the arguments after it are what decide the work.
        std::string arguments = " ";
        arguments += shellCommand(step.arguments);
        const auto found = last.find(step.id);
        if (found == last.end() || !found->second.first.ends_with(arguments))
            prices.emplace_back();
        else
            prices.emplace_back(found->second.second);
    }
    return prices;
}

CostEstimate estimateCost(const Plan& plan, const fs::path& manifest) {
    CostEstimate estimate;
    estimate.hasManifest = fs::is_regular_file(manifest);
    const std::vector<std::optional<double>> prices = stepPrices(plan, manifest);
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        if (!prices[i]) {
            ++estimate.unpriced;
            continue;
        }
        ++estimate.priced;
        estimate.seconds += *prices[i];
        estimate.byKind[plan.steps[i].kind] += *prices[i];
    }
    return estimate;
}

double manifestSeconds(const nlohmann::json& manifest) {
    double seconds = 0;
    for (const nlohmann::json& s : manifest.at("steps")) seconds += s.at("wall_seconds").get<double>();
    return seconds;
}

std::string secondsText(double seconds) {
    char text[32];
    if (seconds < 120)
        std::snprintf(text, sizeof text, "%.1f s", seconds);
    else
        std::snprintf(text, sizeof text, "%.1f min", seconds / 60);
    return text;
}

}  // namespace vri
