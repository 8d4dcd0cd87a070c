// Observed orders of convergence from a step sweep, as Etiene et al. verify volume renderers.
#include "libvri/report/convergence_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/statistics.h"

namespace vri {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The largest absolute error of any channel (vri-diff writes an infinite one as null).
double largestError(const fs::path& diff) {
    const json root = readJsonFile(diff);
    return readingJsonOf(diff, [&] {
        const json& channels = jsonAtPath(root, "channels", diff);
        if (!channels.is_array() || channels.empty()) throw Error(diff.string() + ": has no channels");
        double worst = 0;
        for (const json& channel : channels) {
            const json& value = channel.at("max_abs");
            worst = std::max(worst, value.is_null() ? std::numeric_limits<double>::infinity() : value.get<double>());
        }
        return worst;
    });
}

// The largest per-channel error bound in a run's stats, where it has one (vri-reference's).
std::optional<double> largestBound(const fs::path& stats) {
    if (stats.empty()) return std::nullopt;
    const json root = readJsonFile(stats);
    return readingJsonOf(stats, [&]() -> std::optional<double> {
        if (!root.contains("stats") || !root["stats"].contains("error_bound")) return std::nullopt;
        double worst = 0;
        for (const json& bound : jsonAtPath(root, "stats.error_bound.max", stats)) worst = std::max(worst, bound.get<double>());
        return worst;
    });
}

struct Series {
    std::string name;
    std::vector<double> steps, errors;    // in the order given
    std::optional<double> unstepped;      // the error of a run without a step
    std::optional<double> bound;
    std::optional<double> slope, order;   // over the points above the floor
};

std::vector<Series> measure(const std::vector<ConvergencePoint>& points, double floor) {
    if (points.empty()) throw Error("a convergence table needs at least one point");
    std::vector<Series> all;
    for (const ConvergencePoint& point : points) {
        auto it = std::ranges::find(all, point.series, &Series::name);
        if (it == all.end()) it = all.insert(all.end(), Series{point.series, {}, {}, {}, {}, {}, {}});
        const double error = largestError(point.diff);
        if (point.step && !(*point.step > 0 && std::isfinite(*point.step)))
            throw Error(point.diff.string() + ": series '" + point.series + "': the step must be positive");
        const bool mixed = point.step ? it->unstepped.has_value() : !it->steps.empty() || it->unstepped.has_value();
        if (mixed)
            throw Error(point.diff.string() + ": series '" + point.series +
                        "' takes either runs with a step or one run without");
        if (point.step) {
            it->steps.push_back(*point.step);
            it->errors.push_back(error);
        } else {
            it->unstepped = error;
        }
        if (const std::optional<double> bound = largestBound(point.stats))
            it->bound = std::max(it->bound.value_or(0.0), *bound);
    }
    for (Series& s : all) {
        std::vector<std::pair<double, double>> fitted;  // (h, error) above the floor, by h
        for (std::size_t i = 0; i < s.steps.size(); ++i)
            if (s.errors[i] > floor && std::isfinite(s.errors[i])) fitted.emplace_back(s.steps[i], s.errors[i]);
        std::ranges::sort(fitted);
        if (fitted.size() < 2 || fitted.front().first == fitted.back().first) continue;
        std::vector<double> h, e;
        for (const auto& [step, error] : fitted) h.push_back(step), e.push_back(error);
        s.slope = observedOrder(h, e);
        s.order = std::log(e[1] / e[0]) / std::log(h[1] / h[0]);  // the two smallest steps
    }
    return all;
}

std::string formatNumber(const char* format, double value) {
    char text[32];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

}  // namespace

Table convergenceTable(const std::vector<ConvergencePoint>& points, double floor) {
    Table table;
    table.rowHeader = "series";
    const struct {
        const char* name;
        int precision;
        bool significant;
    } columns[] = {{"points", 0, false},        {"h max", 3, true},         {"h min", 3, true},
                   {"error at h max", 3, true}, {"error at h min", 3, true}, {"observed order", 2, false},
                   {"fitted slope", 2, false},  {"error bound", 2, true}};
    for (const auto& c : columns) {
        table.columns.push_back(c.name);
        table.precision.push_back(c.precision);
        table.significant.push_back(c.significant);
    }
    for (const Series& s : measure(points, floor)) {
        table.rows.push_back(s.name);
        auto& cells = table.cells.emplace_back();
        if (s.unstepped) {
            cells = {std::nullopt, std::nullopt, std::nullopt, std::nullopt, *s.unstepped, std::nullopt, std::nullopt, s.bound};
            continue;
        }
        const auto largest = std::ranges::max_element(s.steps) - s.steps.begin();
        const auto smallest = std::ranges::min_element(s.steps) - s.steps.begin();
        cells = {double(s.steps.size()), s.steps[largest], s.steps[smallest], s.errors[largest], s.errors[smallest],
                 s.order, s.slope, s.bound};
    }
    table.notes.push_back(
        "error: the largest absolute error of any pixel and channel against the accurate reference (vri-diff "
        "max_abs). observed order: log(e1 / e2) / log(h1 / h2) of the two smallest steps h1 < h2; fitted slope: "
        "the least-squares slope of log(error) against log(h) over the sweep (Etiene et al.); both leave out "
        "errors at or below " + formatNumber("%g", floor) + " (float32 rounding of the images), - where fewer "
        "than two points remain. error bound: the largest per-pixel bound the run's stats give (the exact method).");
    return table;
}

std::string convergencePointsCsv(const std::vector<ConvergencePoint>& points, double floor) {
    std::string out = "series,h,error,legend\n";
    for (const Series& s : measure(points, floor)) {
        const std::string legend = s.slope ? s.name + ": slope " + formatNumber("%.2f", *s.slope) : s.name;
        for (std::size_t i = 0; i < s.steps.size(); ++i)
            if (s.errors[i] > floor && std::isfinite(s.errors[i]))
                out += csvField(s.name) + "," + formatNumber("%.17g", s.steps[i]) + "," +
                       formatNumber("%.17g", s.errors[i]) + "," + csvField(legend) + "\n";
    }
    return out;
}

}  // namespace vri
