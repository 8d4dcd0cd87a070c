// Measuring the numbers of a reproduce: block and comparing them with the committed ones.
#include "vri/experiment_reproduce.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "vri/error.h"
#include "vri/image_io.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// Per channel: the largest value and the mean, in double, in a fixed order.
nlohmann::json imageMetrics(const Image& image, const std::vector<std::string>& metrics) {
    nlohmann::json result = nlohmann::json::object();
    for (int c = 0; c < image.channels; ++c) {
        double largest = -INFINITY, sum = 0;
        for (std::size_t i = static_cast<std::size_t>(c); i < image.pixels.size(); i += static_cast<std::size_t>(image.channels)) {
            largest = std::max(largest, static_cast<double>(image.pixels[i]));
            sum += image.pixels[i];
        }
        const double mean = sum / static_cast<double>(image.pixels.size() / static_cast<std::size_t>(image.channels));
        for (const std::string& m : metrics) result[m][image.channelNames[c]] = m == "max" ? largest : mean;
    }
    return result;
}

nlohmann::json diffMetrics(const fs::path& diffJson, const std::vector<std::string>& metrics) {
    std::ifstream in(diffJson);
    if (!in) throw Error(diffJson.string() + ": no such file");
    const nlohmann::json diff = nlohmann::json::parse(in);
    nlohmann::json result = nlohmann::json::object();
    for (const nlohmann::json& channel : diff.at("channels"))
        for (const std::string& m : metrics) result[m][channel.at("name").get<std::string>()] = channel.at(m);
    return result;
}

}  // namespace

nlohmann::json measureReproduceMetrics(const Experiment& experiment, const Plan& plan) {
    nlohmann::json measured = nlohmann::json::object();
    for (const ReproduceCheck& check : experiment.reproduce) {
        const bool isRun = std::any_of(experiment.runs.begin(), experiment.runs.end(), [&](auto& r) { return r.id == check.of; });
        measured[check.of].update(isRun ? imageMetrics(readImage(renderImage(plan, check.of)), check.metrics)
                                        : diffMetrics(plan.resultsDir / (check.of + ".json"), check.metrics));
    }
    return measured;
}

std::vector<std::string> reproduceMismatches(const Experiment& experiment, const nlohmann::json& measured,
                                             const nlohmann::json& committed) {
    std::vector<std::string> problems;
    for (const ReproduceCheck& check : experiment.reproduce) {
        for (const std::string& metric : check.metrics) {
            const nlohmann::json& now = measured.at(check.of).at(metric);
            const std::string what = check.of + " " + metric;
            if (!committed.contains(check.of) || !committed[check.of].contains(metric)) {
                problems.push_back(what + ": no committed value (record them with vri-run --quick --record)");
                continue;
            }
            const nlohmann::json& then = committed[check.of][metric];
            for (const auto& [channel, value] : now.items()) {
                if (!then.contains(channel)) {
                    problems.push_back(what + " " + channel + ": no committed value");
                    continue;
                }
                const double a = value.get<double>(), b = then[channel].get<double>();
                if (!(std::abs(a - b) <= check.tolerance)) {
                    std::ostringstream line;
                    line.precision(17);
                    line << what << " " << channel << ": " << a << ", committed " << b << " (tolerance " << check.tolerance
                         << ")";
                    problems.push_back(line.str());
                }
            }
        }
    }
    return problems;
}

}  // namespace vri
