// Measuring the numbers of a reproduce: block and comparing them with the committed ones.
#include "libvri/experiment/experiment_reproduce.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "libvri/io/image_io.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"

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
    const nlohmann::json diff = readJsonFile(diffJson);
    return readingJsonOf(diffJson, [&] {
        nlohmann::json result = nlohmann::json::object();
        for (const nlohmann::json& channel : diff.at("channels"))
            for (const std::string& m : metrics) result[m][channel.at("name").get<std::string>()] = channel.at(m);
        return result;
    });
}

// Every cell of a CSV file, by column: numbers as numbers, anything else as text.
nlohmann::json csvCells(const fs::path& path) {
    const CsvFile csv = readCsv(path);
    nlohmann::json columns = nlohmann::json::object();
    for (std::size_t c = 0; c < csv.header.size(); ++c) {
        nlohmann::json cells = nlohmann::json::array();
        for (const auto& row : csv.rows) {
            const std::string field = c < row.size() ? row[c] : "";
            const auto value = parseNumber(field);
            cells.push_back(value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json(field));
        }
        columns[csv.header[c]] = std::move(cells);
    }
    return columns;
}

// A file's cells against the committed ones: the same columns and rows, numbers within tolerance.
void compareCells(const std::string& what, const nlohmann::json& now, const nlohmann::json& then, double tolerance,
                  std::vector<std::string>& problems) {
    for (const auto& [column, cells] : now.items()) {
        if (!then.contains(column) || then[column].size() != cells.size()) {
            problems.push_back(what + " " + column + ": the committed file has no such column, or other rows");
            continue;
        }
        for (std::size_t row = 0; row < cells.size(); ++row) {
            const nlohmann::json &a = cells[row], &b = then[column][row];
            const bool same = a.is_number() && b.is_number() ? std::abs(a.get<double>() - b.get<double>()) <= tolerance
                                                             : a == b;
            if (!same) {
                problems.push_back(what + " " + column + " row " + std::to_string(row + 1) + ": " + a.dump() +
                                   ", committed " + b.dump() + " (tolerance " + std::to_string(tolerance) + ")");
                return;  // the first difference of a file says enough
            }
        }
    }
}

}  // namespace

Plan checkedPart(const Experiment& experiment, const Plan& plan, const std::set<fs::path>& readElsewhere) {
    if (experiment.reproduce.empty()) return plan;
    std::vector<bool> needed(plan.steps.size(), false);
    for (std::size_t i = plan.steps.size(); i-- > 0;) {  // a step comes after those it depends on
        const Step& step = plan.steps[i];
        needed[i] = needed[i] ||
                    std::any_of(experiment.reproduce.begin(), experiment.reproduce.end(),
                                [&](const ReproduceCheck& check) { return check.of == step.id; }) ||
                    std::any_of(step.outputs.begin(), step.outputs.end(),
                                [&](const fs::path& out) { return readElsewhere.count(out) > 0; });
        if (needed[i])
            for (std::size_t d : plan.dependencies[i]) needed[d] = true;
    }
    Plan part{plan.resultsDir, plan.workDir, {}, {}};
    std::vector<std::size_t> index(plan.steps.size());
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        if (!needed[i]) continue;
        index[i] = part.steps.size();
        part.steps.push_back(plan.steps[i]);
        std::vector<std::size_t> dependencies;
        for (std::size_t d : plan.dependencies[i]) dependencies.push_back(index[d]);
        part.dependencies.push_back(std::move(dependencies));
    }
    part.part = std::to_string(part.steps.size()) + " of its " + std::to_string(plan.steps.size()) +
                " steps: those its reproduce: numbers need (vri-run --check)";
    return part;
}

nlohmann::json measureReproduceMetrics(const Experiment& experiment, const Plan& plan) {
    nlohmann::json measured = nlohmann::json::object();
    for (const ReproduceCheck& check : experiment.reproduce) {
        if (!check.file.empty()) {
            measured[check.of][check.file] = csvCells(plan.resultsDir / check.file);
            continue;
        }
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
        if (!check.file.empty()) {
            const std::string what = check.of + " " + check.file;
            if (!committed.contains(check.of) || !committed[check.of].contains(check.file))
                problems.push_back(what + ": no committed values (record them with vri-run --quick --record)");
            else
                compareCells(what, measured.at(check.of).at(check.file), committed[check.of][check.file], check.tolerance,
                             problems);
            continue;
        }
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
