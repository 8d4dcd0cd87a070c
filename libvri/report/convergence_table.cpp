// Observed orders of convergence from a step sweep, as Etiene et al. verify volume renderers.
#include "libvri/report/convergence_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "libvri/render/stats_schema.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/statistics.h"

namespace vri {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The largest absolute error of any pixel and channel, and the mean absolute error over pixels and
// channels (vri-diff writes an infinite one as null).
struct Errors {
    double max = 0, mean = 0;
};
Errors imageErrors(const fs::path& diff) {
    const json root = readJsonFile(diff);
    return readingJsonOf(diff, [&] {
        const json& channels = jsonAtPath(root, "channels", diff);
        if (!channels.is_array() || channels.empty()) throw Error(diff.string() + ": has no channels");
        const auto number = [](const json& value) {
            return value.is_null() ? std::numeric_limits<double>::infinity() : value.get<double>();
        };
        Errors e;
        for (const json& channel : channels) {
            e.max = std::max(e.max, number(channel.at("max_abs")));
            e.mean += number(channel.at("mean_abs"));
        }
        e.mean /= static_cast<double>(channels.size());
        return e;
    });
}

// The largest per-channel error bound in a run's stats, where it has one (vri-reference's).
std::optional<double> largestBound(const fs::path& stats) {
    if (stats.empty()) return std::nullopt;
    const json root = readJsonFile(stats);
    return readingJsonOf(stats, [&]() -> std::optional<double> {
        if (!root.contains(stats_field::errorBoundMax.at())) return std::nullopt;
        double worst = 0;
        for (const json& bound : root.at(stats_field::errorBoundMax.at())) worst = std::max(worst, bound.get<double>());
        return worst;
    });
}

// The slope of log error against log h over the asymptotic range, the kConvergenceFitSteps smallest steps
// whose error is above the floor, and the largest step of that range; none where fewer than two remain.
// The (h, error) points whose error is above the floor (and finite), smallest h first.
std::vector<std::pair<double, double>> pointsAbove(const std::vector<double>& steps, const std::vector<double>& errors,
                                                   double floor) {
    std::vector<std::pair<double, double>> usable;
    for (std::size_t i = 0; i < steps.size(); ++i)
        if (errors[i] > floor && std::isfinite(errors[i])) usable.emplace_back(steps[i], errors[i]);
    std::ranges::sort(usable);
    return usable;
}

std::pair<std::optional<double>, std::optional<double>> asymptoticOrder(const std::vector<double>& steps,
                                                                         const std::vector<double>& errors, double floor) {
    std::vector<std::pair<double, double>> usable = pointsAbove(steps, errors, floor);
    if (usable.size() > kConvergenceFitSteps) usable.resize(kConvergenceFitSteps);
    if (usable.size() < 2 || usable.front().first == usable.back().first) return {};
    std::vector<double> h, e;
    for (const auto& [step, error] : usable) h.push_back(step), e.push_back(error);
    return {observedOrder(h, e), h.back()};
}

// The order between each two neighbouring steps, log(e_i / e_i+1) / log(h_i / h_i+1), largest h first, over the
// steps whose error is above the floor: a fit over a few steps can straddle a change of order that these show.
std::vector<double> localOrders(const std::vector<double>& steps, const std::vector<double>& errors, double floor) {
    std::vector<std::pair<double, double>> usable = pointsAbove(steps, errors, floor);
    std::ranges::reverse(usable);  // largest h first
    std::vector<double> orders;
    for (std::size_t i = 0; i + 1 < usable.size(); ++i)
        if (usable[i].first != usable[i + 1].first)
            orders.push_back(std::log(usable[i].second / usable[i + 1].second) / std::log(usable[i].first / usable[i + 1].first));
    return orders;
}

struct Series {
    std::string name;
    std::vector<double> steps;            // in the order given
    std::vector<Errors> errors;
    std::optional<Errors> unstepped;      // the error of a run without a step
    std::optional<double> bound;
    std::optional<double> maxOrder, meanOrder;     // over the asymptotic range (convergence_table.h)
    std::optional<double> maxFitFrom, meanFitFrom;  // the largest step of that range
    std::vector<double> maxLocalOrders;             // localOrders() of the max error
};

std::vector<Series> measure(const std::vector<ConvergencePoint>& points, double floor) {
    if (points.empty()) throw Error("a convergence table needs at least one point");
    std::vector<Series> all;
    for (const ConvergencePoint& point : points) {
        auto it = std::ranges::find(all, point.series, &Series::name);
        if (it == all.end()) it = all.insert(all.end(), Series{point.series, {}, {}, {}, {}, {}, {}, {}, {}, {}});
        const Errors errors = imageErrors(point.diff);
        if (point.step && !(*point.step > 0 && std::isfinite(*point.step)))
            throw Error(point.diff.string() + ": series '" + point.series + "': the step must be positive");
        const bool mixed = point.step ? it->unstepped.has_value() : !it->steps.empty() || it->unstepped.has_value();
        if (mixed)
            throw Error(point.diff.string() + ": series '" + point.series +
                        "' takes either runs with a step or one run without");
        if (point.step) {
            it->steps.push_back(*point.step);
            it->errors.push_back(errors);
        } else {
            it->unstepped = errors;
        }
        if (const std::optional<double> bound = largestBound(point.stats))
            it->bound = std::max(it->bound.value_or(0.0), *bound);
    }
    for (Series& s : all) {
        std::vector<double> largest, mean;
        for (const Errors& e : s.errors) largest.push_back(e.max), mean.push_back(e.mean);
        std::tie(s.maxOrder, s.maxFitFrom) = asymptoticOrder(s.steps, largest, floor);
        s.maxLocalOrders = localOrders(s.steps, largest, floor);
        std::tie(s.meanOrder, s.meanFitFrom) = asymptoticOrder(s.steps, mean, kConvergenceMeanFloor);
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
    } columns[] = {{"points", 0, false},          {"h max", 3, true},           {"h min", 3, true},
                   {"max error at h max", 3, true}, {"max error at h min", 3, true}, {"max order", 2, false},
                   {"max fitted from h", 3, true}, {"mean error at h max", 3, true}, {"mean error at h min", 3, true},
                   {"mean order", 2, false},       {"mean fitted from h", 3, true}, {"error bound", 2, true},
                   {"min local order", 2, false},  {"max local order", 2, false}};
    for (const auto& c : columns) {
        table.columns.push_back(c.name);
        table.precision.push_back(c.precision);
        table.significant.push_back(c.significant);
    }
    table.textColumns = {"local max orders"};
    for (const Series& s : measure(points, floor)) {
        table.rows.push_back(s.name);
        std::string local;
        for (double order : s.maxLocalOrders) local += (local.empty() ? "" : " ") + formatNumber("%.2f", order);
        table.texts.push_back({local.empty() ? "-" : local});
        auto& cells = table.cells.emplace_back();
        if (s.unstepped) {
            cells = {std::nullopt, std::nullopt,      std::nullopt, std::nullopt, s.unstepped->max, std::nullopt,
                     std::nullopt, std::nullopt,      s.unstepped->mean, std::nullopt, std::nullopt, s.bound,
                     std::nullopt, std::nullopt};
            continue;
        }
        std::optional<double> leastLocal, mostLocal;
        if (!s.maxLocalOrders.empty()) {
            leastLocal = *std::ranges::min_element(s.maxLocalOrders);
            mostLocal = *std::ranges::max_element(s.maxLocalOrders);
        }
        const auto largest = std::ranges::max_element(s.steps) - s.steps.begin();
        const auto smallest = std::ranges::min_element(s.steps) - s.steps.begin();
        cells = {double(s.steps.size()), s.steps[largest],       s.steps[smallest],      s.errors[largest].max,
                 s.errors[smallest].max, s.maxOrder,             s.maxFitFrom,           s.errors[largest].mean,
                 s.errors[smallest].mean, s.meanOrder,           s.meanFitFrom,          s.bound,
                 leastLocal,              mostLocal};
    }
    table.notes.push_back(
        "max error: the largest absolute error of any pixel and channel against the accurate reference (vri-diff "
        "max_abs); mean error: the mean absolute error over pixels and channels (mean_abs). max order, mean order: "
        "the least-squares slope of log(error) against log(h) (Etiene et al.) over the asymptotic range, the " +
        std::to_string(kConvergenceFitSteps) + " smallest steps whose error is above float32 rounding of the images (" +
        formatNumber("%g", floor) + " for the max, " + formatNumber("%.2g", kConvergenceMeanFloor) +
        " for the mean), from the step 'fitted from h' down; - where fewer than two remain. local max orders: the "
        "order of the max error between each two neighbouring steps above that floor, largest h first, and their "
        "least and largest: where they scatter, the fitted order holds over no range of h. error bound: the "
        "largest per-pixel bound the run's stats give (the exact method).");
    return table;
}

std::string convergencePointsCsv(const std::vector<ConvergencePoint>& points, double floor) {
    std::string out = "series,h,error,legend\n";
    for (const Series& s : measure(points, floor)) {
        const std::string legend = s.maxOrder ? s.name + ": max order " + formatNumber("%.2f", *s.maxOrder) : s.name;
        for (std::size_t i = 0; i < s.steps.size(); ++i)
            if (s.errors[i].max > floor && std::isfinite(s.errors[i].max))
                out += csvField(s.name) + "," + formatNumber("%.17g", s.steps[i]) + "," +
                       formatNumber("%.17g", s.errors[i].max) + "," + csvField(legend) + "\n";
    }
    return out;
}

}  // namespace vri
