// Pricing an experiment's steps from the wall times its last manifest recorded.
#include "libvri/experiment/step_costs.h"

#include <cstdio>
#include <map>

#include "libvri/util/json_file.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// A command without where its files lie: every word's folders dropped ("../data/bonsai.raw" and
// "/mnt/v/bonsai.raw" both "bonsai.raw"), so that a price holds when the data or the results move
// (VRI_DATA_DIR, the Makefile's data/ fallback, another results root); the file names, sizes, methods
// and every other argument still decide.
std::string commandShape(const std::string& command) {
    std::string shape;
    std::size_t start = 0;
    while (start <= command.size()) {
        std::size_t end = command.find(' ', start);
        if (end == std::string::npos) end = command.size();
        std::string word = command.substr(start, end - start);
        if (const std::size_t slash = word.rfind('/'); slash != std::string::npos) {
            const bool quoted = !word.empty() && word.front() == '\'';  // shellCommand quotes a word whole
            word = (quoted ? "'" : "") + word.substr(slash + 1);
        }
        shape += (shape.empty() ? "" : " ") + word;
        start = end + 1;
    }
    return shape;
}

}  // namespace

std::vector<std::optional<double>> stepPrices(const Plan& plan, const fs::path& manifest) {
    // id -> {command, seconds} of the last run
    std::map<std::string, std::pair<std::string, double>> last;
    if (fs::is_regular_file(manifest)) {
        const nlohmann::json m = readJsonFile(manifest);
        readingJsonOf(manifest, [&] {
            for (const nlohmann::json& s : m.at("steps")) {
                // A price only from a time a step can have taken: one edited to 1e300 or -1e6 (a Slurm job's
                // --time is made from it) leaves the step unpriced, as a step never run.
                const double seconds = s.at("wall_seconds").get<double>();
                if (seconds >= 0 && seconds <= kMostStepSeconds)
                    last[s.at("id").get<std::string>()] = {s.at("command").get<std::string>(), seconds};
            }
        });
    }
    std::vector<std::optional<double>> prices;
    for (const Step& step : plan.steps) {
        // The manifest's command starts with the tool as the run that wrote it named it (its build
        // folder); the arguments after it, wherever their files lie, are what decide the work.
        const std::string arguments = " " + commandShape(shellCommand(step.arguments));
        const auto found = last.find(step.id);
        if (found == last.end() || !commandShape(found->second.first).ends_with(arguments))
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
