// Building the papers' tables, and the speed-against-accuracy table, from the JSON that vri-diff and
// vri-render write.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "libvri/render/render_job.h"  // medianInterval
#include "libvri/render/stats_schema.h"
#include "libvri/report/pareto.h"
#include "libvri/report/table.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/statistics.h"

namespace vri {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

double numberAt(const json& root, const std::string& path, const fs::path& file) {
    const json& node = jsonAtPath(root, path, file);
    // vri-diff writes infinite errors as null: JSON has no infinity.
    if (node.is_null()) return std::numeric_limits<double>::infinity();
    if (!node.is_number()) throw Error(file.string() + ": '" + path + "' is not a number");
    return node.get<double>();
}

struct ValueExpression {
    std::string path;
    bool reciprocal = false;
};

ValueExpression parseExpression(const std::string& expression) {
    const bool reciprocal = expression.starts_with("1/");
    ValueExpression parsed{reciprocal ? expression.substr(2) : expression, reciprocal};
    if (parsed.path.empty())
        throw Error("value '" + expression + "': expected a dotted JSON path, e.g. " + stats_field::wallSeconds.dotted());
    requireStatsField(parsed.path, "value '" + expression + "'");
    return parsed;
}

std::string formatThreshold(double threshold) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", threshold);
    return text;
}

std::vector<std::string> channelNames(const json& diff, const fs::path& file) {
    return readingJsonOf(file, [&] {
        std::vector<std::string> names;
        for (const json& channel : jsonAtPath(diff, "channels", file)) names.push_back(channel.at("name").get<std::string>());
        return names;
    });
}

// The % of pixels whose error in `channel` exceeds `threshold`.
double percentAbove(const json& diff, std::size_t channel, double threshold, const fs::path& file) {
    const std::optional<double> percent = readingJsonOf(file, [&]() -> std::optional<double> {
        for (const json& above : jsonAtPath(diff, "channels." + std::to_string(channel) + ".above", file))
            if (above.at("threshold").get<double>() == threshold) return above.at("percent").get<double>();
        return std::nullopt;
    });
    if (percent) return *percent;
    throw Error(file.string() + ": no count above " + formatThreshold(threshold) +
                " (run vri-diff with --threshold including it)");
}

template <class T>
std::size_t indexOf(std::vector<T>& list, const T& item) {
    auto it = std::find(list.begin(), list.end(), item);
    if (it == list.end()) it = list.insert(list.end(), item);
    return static_cast<std::size_t>(it - list.begin());
}

std::string medianNote(std::size_t fewest, std::size_t most) {
    if (most <= 1) return {};
    const std::string count = fewest == most ? std::to_string(most) : std::to_string(fewest) + " to " + std::to_string(most);
    return "Each cell is the median of " + count + " runs.";
}

// A run's method family from its stats, what one series of a chart draws: "riemann float SIMD",
// "riemann float SIMD AVX2" (a forced target), "exact AVX2" (its Gauss batches on a forced target),
// "coupled double", "riemann float vulkan", "exact" (vri-reference's stats name no backend), "vtk-gpu",
// "preintegrated double order 2", "riemann double jitter 4 frames".
std::string methodFamily(const json& stats, const fs::path& file) {
    return readingJsonOf(file, [&] {
        const json& options = stats.at("options");
        const std::string method = options.at("method").get<std::string>();
        // The exact method's Gauss batches on a target forced below the best: "exact AVX2".
        if (method == "exact")
            return options.contains("simd_target") ? method + " " + options.at("simd_target").get<std::string>() : method;
        // A peer renderer (vri-peer-vtk) has no precision option: its family is its method.
        if (!options.contains("precision")) return method;
        // An outside renderer (vri-outside): its name; the card's method is what it was asked to compute.
        using namespace stats_field;
        const std::string runBackend = stats.value(backend.at(), "cpu");
        if (runBackend == "outside") return stats.at("renderer").at("name").get<std::string>();
        std::string family = method + " " + options.at("precision").get<std::string>();
        if (runBackend == "vulkan") family += " vulkan";
        else if (stats.contains(simdTarget.at()) && !stats.at(simdTarget.at()).is_null()) family += " SIMD";
        // A target forced below the best (--simd AVX2) is a family of its own, so that a chart or a
        // table's rows keep one host's targets apart.
        if (options.contains("simd_target")) family += " " + options.at("simd_target").get<std::string>();
        // Second-order pre-integration and jittered sampling are methods of their own on a chart, and so is
        // the mean of several jittered frames (a frame costs N renders): unmarked, a family's line would join
        // them with the plain runs it is compared against.
        if (options.value("preint_order", 1) == 2) family += " order 2";
        if (options.value("jitter", false)) {
            family += " jitter";
            if (const int frames = options.value("frames", 1); frames > 1) family += " " + std::to_string(frames) + " frames";
        }
        return family;
    });
}

// What a reader of seconds needs to know of the host, from a run's machine record (provenance.h): its CPU,
// the vector extensions it has and the SIMD targets vri could run on it; empty for a record without them.
std::string hostNote(const json& stats) {
    if (!stats.contains("machine") || !stats["machine"].is_object()) return {};
    const json& machine = stats["machine"];
    const auto list = [&](const char* key) {
        std::string text;
        if (machine.contains(key) && machine[key].is_array())
            for (const json& item : machine[key])
                if (item.is_string()) text += (text.empty() ? "" : " ") + item.get<std::string>();
        return text;
    };
    if (!machine.contains("cpu_model") || !machine["cpu_model"].is_string()) return {};
    std::string note = "host: " + machine["cpu_model"].get<std::string>();
    if (machine.contains("usable_cores") && machine["usable_cores"].is_number_integer())
        note += ", " + std::to_string(machine["usable_cores"].get<long long>()) + " usable cores";
    if (const std::string flags = list("cpu_simd_flags"); !flags.empty()) note += "; CPU flags: " + flags;
    if (const std::string targets = list("simd_targets"); !targets.empty())
        note += "; SIMD targets, best first: " + targets;
    return note + ".";
}

}  // namespace

double readJsonValue(const fs::path& file, const std::string& expression) {
    const ValueExpression parsed = parseExpression(expression);
    const double value = numberAt(readJsonFile(file), parsed.path, file);
    return parsed.reciprocal ? 1.0 / value : value;
}

namespace {

// How a table's percentages are printed, for its note: ", to 3 significant digits (0: no ray)".
std::string digitsNote(const std::optional<int>& decimals) {
    if (decimals) return ", to " + std::to_string(*decimals) + " decimals";
    return ", to " + std::to_string(kPercentDigits) + " significant digits (0: no ray)";
}

// A warning for a table of times when any of its runs was timed beside other processes that kept the cores
// busy (timing.load.overloaded, frame_timing.h); empty when none was, or the stats do not say.
std::string loadWarning(const std::vector<fs::path>& statsFiles) {
    std::size_t loaded = 0;
    double most = 0;
    for (const fs::path& file : statsFiles) {
        const std::optional<TimingLoad> load = timingLoadOf(readJsonFile(file));
        if (!load || !load->overloaded()) continue;
        ++loaded;
        most = std::max(most, load->otherCores);
    }
    if (loaded == 0) return {};
    char cores[32];
    std::snprintf(cores, sizeof cores, "%.1f", most);
    return "Warning: " + std::to_string(loaded) + " of these " + std::to_string(statsFiles.size()) +
           " runs were timed while other processes kept the cores busy (up to " + cores +
           " cores beside their threads; timing.load in each run's stats): their seconds are inflated.";
}

// Which pixels a comparison's percentages count, from its vri-diff JSON: "all pixels, background included",
// or its --mask's description.
std::string pixelsCounted(const json& diff) {
    const std::string counted = diff.value("pixels_counted", "all");
    return counted == "all" ? "all pixels, background included" : counted;
}

}  // namespace

Table thresholdTable(const std::vector<ThresholdRow>& rows, std::vector<double> thresholds, std::optional<int> decimals) {
    if (rows.empty()) throw Error("a threshold table needs at least one row");
    const fs::path& first = rows.front().files.at(0);
    const json firstDiff = readJsonFile(first);
    if (thresholds.empty())
        readingJsonOf(first, [&] {
            for (const json& t : jsonAtPath(firstDiff, "thresholds", first)) thresholds.push_back(t.get<double>());
        });
    const std::vector<std::string> channels = channelNames(firstDiff, first);

    Table table;
    table.rowHeader = "Method";
    for (double threshold : thresholds)
        for (const std::string& channel : channels) {
            table.columns.push_back(channel + " > " + formatThreshold(threshold));
            table.precision.push_back(decimals.value_or(kPercentDigits));
            table.significant.push_back(!decimals);
        }
    for (const ThresholdRow& row : rows) {
        if (row.files.size() != 1 && row.files.size() != thresholds.size())
            throw Error("row '" + row.label + "': " + std::to_string(row.files.size()) +
                        " files; expected 1 or one per threshold (" + std::to_string(thresholds.size()) + ")");
        std::vector<json> diffs;
        for (const fs::path& file : row.files) {
            diffs.push_back(readJsonFile(file));
            if (channelNames(diffs.back(), file) != channels)
                throw Error(file.string() + ": its channels differ from those of " + first.string());
        }
        table.rows.push_back(row.label);
        auto& cells = table.cells.emplace_back();
        for (std::size_t t = 0; t < thresholds.size(); ++t) {
            const std::size_t which = row.files.size() == 1 ? 0 : t;
            for (std::size_t c = 0; c < channels.size(); ++c)
                cells.push_back(percentAbove(diffs[which], c, thresholds[t], row.files[which]));
        }
    }
    table.notes.push_back("Percentage of rays (" + pixelsCounted(firstDiff) +
                          ") whose absolute error exceeds the threshold, per channel" + digitsNote(decimals) + ".");
    return table;
}

Table matrixTable(const std::vector<MatrixCell>& cells, const MatrixOptions& options) {
    Table table;
    table.rowHeader = "Method";
    std::set<std::pair<std::string, std::string>> seen;
    for (const MatrixCell& cell : cells) {
        if (!seen.insert({cell.row, cell.column}).second)
            throw Error("cell (" + cell.row + ", " + cell.column + ") is given twice; list all its files at once");
        indexOf(table.rows, cell.row);
        indexOf(table.columns, cell.column);
    }
    for (const auto& [column, expression] : options.columnValue)
        if (std::find(table.columns.begin(), table.columns.end(), column) == table.columns.end())
            throw Error("value for column '" + column + "': no such column");
    for (const auto& [column, decimals] : options.columnPrecision)
        if (std::find(table.columns.begin(), table.columns.end(), column) == table.columns.end())
            throw Error("precision for column '" + column + "': no such column");

    auto valueOf = [&](const std::string& column) {
        const auto it = options.columnValue.find(column);
        return it == options.columnValue.end() ? options.value : it->second;
    };
    table.cells.assign(table.rows.size(), std::vector<std::optional<double>>(table.columns.size()));
    for (const std::string& column : table.columns) {
        const auto it = options.columnPrecision.find(column);
        table.precision.push_back(it == options.columnPrecision.end() ? options.precision : it->second);
    }
    std::size_t fewest = std::numeric_limits<std::size_t>::max(), most = 0;
    for (const MatrixCell& cell : cells) {
        if (cell.files.empty()) throw Error("cell (" + cell.row + ", " + cell.column + ") has no files");
        const ValueExpression expression = parseExpression(valueOf(cell.column));
        std::vector<double> values;
        for (const fs::path& file : cell.files) values.push_back(numberAt(readJsonFile(file), expression.path, file));
        const double middle = median(values);
        table.cells[indexOf(table.rows, cell.row)][indexOf(table.columns, cell.column)] =
            expression.reciprocal ? 1.0 / middle : middle;
        fewest = std::min(fewest, cell.files.size());
        most = std::max(most, cell.files.size());
    }

    std::string values = "Values: " + options.value;
    if (!options.columnValue.empty()) {
        values = "Values:";
        for (const std::string& column : table.columns) values += " " + column + ": " + valueOf(column) + ";";
        values.pop_back();
    }
    table.notes.push_back(values + ".");
    if (const std::string note = medianNote(fewest, most); !note.empty()) table.notes.push_back(note);
    bool timed = options.value.find("timing.") != std::string::npos;
    for (const auto& [column, expression] : options.columnValue) timed = timed || expression.find("timing.") != std::string::npos;
    if (timed) {
        std::vector<fs::path> files;
        for (const MatrixCell& cell : cells) files.insert(files.end(), cell.files.begin(), cell.files.end());
        if (const std::string warning = loadWarning(files); !warning.empty()) table.notes.push_back(warning);
    }
    return table;
}

Table tradeoffTable(const std::vector<TradeoffRow>& rows, const TradeoffOptions& options) {
    if (rows.empty()) throw Error("a tradeoff table needs at least one row");
    if (options.thresholds.empty()) throw Error("a tradeoff table needs at least one threshold");
    const fs::path& first = rows.front().diff;
    const std::vector<std::string> channels = channelNames(readJsonFile(first), first);
    if (channels.empty()) throw Error(first.string() + ": has no channels");
    const auto above = [](double t) { return " > " + formatThreshold(t); };
    constexpr int kDigits = 4;  // significant digits of times, rates and errors
    const auto baseline = std::ranges::find(rows, options.baseline, &TradeoffRow::label);
    if (!options.baseline.empty() && baseline == rows.end())
        throw Error("baseline '" + options.baseline + "': no row of that name");

    Table table;
    table.rowHeader = "run";
    table.textColumns = {"method"};
    auto addColumn = [&](const std::string& name, int digits, bool significant) {
        table.columns.push_back(name);
        table.precision.push_back(digits);
        table.significant.push_back(significant);
    };
    // The exact method's per-pixel error bound, where a row has one: its tolerance is no bound.
    const bool anyBound = std::ranges::any_of(rows, [](const TradeoffRow& row) {
        const json stats = readJsonFile(row.stats);
        return stats.contains(stats_field::errorBoundMax.at());
    });
    addColumn("seconds", kDigits, true);
    addColumn("frames", 0, false);
    addColumn("spread %", 2, true);
    addColumn("ci low", kDigits, true);
    addColumn("ci high", kDigits, true);
    if (!options.baseline.empty()) addColumn("time ratio", kDigits, true);
    addColumn("Msamples/s", kDigits, true);
    for (double t : options.thresholds) {
        if (options.perChannel)
            for (const std::string& channel : channels)
                addColumn(channel + above(t), options.decimals.value_or(kPercentDigits), !options.decimals);
        addColumn("worst" + above(t), options.decimals.value_or(kPercentDigits), !options.decimals);
    }
    if (options.perChannel)
        for (const std::string& channel : channels) addColumn("max " + channel, kDigits, true);
    addColumn("max", kDigits, true);
    addColumn("rmse", kDigits, true);
    // The metrics the field reads (image_metrics.h), when the diffs carry them: rankings can differ by metric.
    const bool anyMetrics = std::ranges::any_of(rows, [](const TradeoffRow& row) { return readJsonFile(row.diff).contains("metrics"); });
    if (anyMetrics)
        for (const char* name : {"PSNR dB", "SSIM", "FLIP"}) addColumn(name, kDigits, true);
    if (anyBound) addColumn("bound", kDigits, true);
    addColumn("pareto %", 0, false);
    addColumn("pareto max", 0, false);

    const auto secondsOf = [](const TradeoffRow& row) {
        return numberAt(readJsonFile(row.stats), stats_field::medianFrameSeconds.dotted(), row.stats);
    };
    const double baselineSeconds = options.baseline.empty() ? 0.0 : secondsOf(*baseline);
    if (!options.baseline.empty() && !(baselineSeconds > 0))
        throw Error(baseline->stats.string() + ": the baseline's time per frame is not positive");
    std::vector<std::pair<double, double>> byPercent, byMax;  // (seconds, error) per row
    for (const TradeoffRow& row : rows) {
        const json diff = readJsonFile(row.diff);
        if (channelNames(diff, row.diff) != channels)
            throw Error(row.diff.string() + ": its channels differ from those of " + first.string());
        const json stats = readJsonFile(row.stats);
        const double seconds = numberAt(stats, stats_field::medianFrameSeconds.dotted(), row.stats);
        table.rows.push_back(row.label);
        table.texts.push_back({methodFamily(stats, row.stats)});
        auto& cells = table.cells.emplace_back();
        cells.push_back(seconds);
        // How far one frame's time strays: (slowest - fastest) / median over the timed frames; 0 for one frame.
        std::vector<double> times;
        for (const json& t : jsonAtPath(stats, stats_field::frameSeconds.dotted(), row.stats)) times.push_back(t.get<double>());
        if (times.empty()) throw Error(row.stats.string() + ": " + stats_field::frameSeconds.dotted() + " has no frame");
        const auto [fastest, slowest] = std::ranges::minmax(times);
        cells.push_back(static_cast<double>(times.size()));
        cells.push_back(seconds > 0 ? 100 * (slowest - fastest) / seconds : 0.0);
        const MedianInterval ci = medianInterval(times);
        cells.push_back(ci.low);
        cells.push_back(ci.high);
        if (!options.baseline.empty()) cells.push_back(seconds / baselineSeconds);
        if (stats.contains(stats_field::samplesEvaluated.at()) && seconds > 0)
            cells.push_back(numberAt(stats, stats_field::samplesEvaluated.dotted(), row.stats) / seconds / 1e6);
        else
            cells.emplace_back();
        for (std::size_t t = 0; t < options.thresholds.size(); ++t) {
            double worst = 0;
            for (std::size_t c = 0; c < channels.size(); ++c) {
                const double percent = percentAbove(diff, c, options.thresholds[t], row.diff);
                worst = std::max(worst, percent);
                if (options.perChannel) cells.push_back(percent);
            }
            cells.push_back(worst);
            if (t == 0) byPercent.emplace_back(seconds, worst);
        }
        double worstMax = 0, worstRmse = 0;
        for (std::size_t c = 0; c < channels.size(); ++c) {
            const double max = numberAt(diff, "channels." + std::to_string(c) + ".max_abs", row.diff);
            worstMax = std::max(worstMax, max);
            worstRmse = std::max(worstRmse, numberAt(diff, "channels." + std::to_string(c) + ".rmse", row.diff));
            if (options.perChannel) cells.push_back(max);
        }
        cells.push_back(worstMax);
        cells.push_back(worstRmse);
        for (const char* path : {"/metrics/all/psnr_db", "/metrics/all/ssim", "/metrics/flip/ldr/mean"}) {
            if (!anyMetrics) break;
            const json::json_pointer pointer(path);
            if (diff.contains(pointer) && diff.at(pointer).is_number()) cells.push_back(diff.at(pointer).get<double>());
            else cells.emplace_back();  // equal images (an infinite PSNR), or a diff made before the metrics
        }
        if (anyBound) {
            if (stats.contains(stats_field::errorBoundMax.at())) {
                double bound = 0;
                for (const json& b : stats.at(stats_field::errorBoundMax.at())) bound = std::max(bound, b.get<double>());
                cells.push_back(bound);
            } else {
                cells.emplace_back();
            }
        }
        byMax.emplace_back(seconds, worstMax);
    }
    std::vector<double> onPercent(rows.size(), 0), onMax(rows.size(), 0);
    for (std::size_t r : paretoFront(byPercent)) onPercent[r] = 1;
    for (std::size_t r : paretoFront(byMax)) onMax[r] = 1;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        table.cells[r].push_back(onPercent[r]);
        table.cells[r].push_back(onMax[r]);
    }

    const std::string front = "worst" + above(options.thresholds.front());
    table.notes.push_back("method: the run's method and precision, SIMD where the float packets ran (and the SIMD "
                          "target when a run asked for one below the best), vulkan on that backend. seconds: median "
                          "wall time per frame (the run's timing.median_wall_seconds); frames: the timed frames it is "
                          "the median of (after the run's warm-up frames); spread %: (slowest - fastest frame) / "
                          "median, 0 for one frame, whose time is one sample." +
                          (options.baseline.empty() ? std::string()
                                                    : " time ratio: seconds over those of " + options.baseline +
                                                          ", timed in the same run."));
    table.notes.push_back("ci low, ci high: the frames' order statistics that hold the median time with a known "
                          "chance, whatever the times' distribution: the fastest and slowest of 3 frames (75 %) or "
                          "of 5 (94 %); from 6 frames on, the narrowest such pair that holds it with at least 95 % "
                          "(timing.median_ci).");
    table.notes.push_back("Msamples/s: millions of samples evaluated per second (stats.samples_evaluated over "
                          "seconds; - where the method counts none).");
    if (anyMetrics)
        table.notes.push_back("PSNR dB (peak 1; - for equal images), SSIM (Wang et al. 2004, the channels' mean) and FLIP "
                          "(LDR-FLIP's mean over R, G, B, Andersson et al. 2020): vri-diff's metrics over the pixels "
                          "the comparison counts.");
    std::vector<fs::path> statsFiles;
    for (const TradeoffRow& row : rows) statsFiles.push_back(row.stats);
    if (const std::string warning = loadWarning(statsFiles); !warning.empty()) table.notes.push_back(warning);
    if (const std::string host = hostNote(readJsonFile(rows.front().stats)); !host.empty()) table.notes.push_back(host);
    std::string percents;
    for (double t : options.thresholds) percents += (percents.empty() ? "" : ", ") + formatThreshold(t);
    const std::string rays = "% of rays (" + pixelsCounted(readJsonFile(rows.front().diff)) +
                             ") whose absolute error exceeds t (t = " + percents + ")" + digitsNote(options.decimals);
    if (options.perChannel)
        table.notes.push_back(channels.front() + " > t ... worst > t: " + rays + ", per channel and in the worst "
                              "channel; max " + channels.front() + " ... max: the largest absolute error, per channel "
                              "and over all; rmse: the largest root mean square error of a channel.");
    else
        table.notes.push_back("worst > t: " + rays + " in the worst channel; max: the largest absolute error; rmse: "
                              "the largest root mean square error of a channel.");
    if (anyBound)
        table.notes.push_back("bound: the exact method's per-pixel error bound, the largest over the pixels and channels "
                              "(stats.error_bound.max; rigorous); its tolerance is not one. - for the other methods.");
    table.notes.push_back("pareto % (pareto max): 1 on the Pareto front of seconds against " + front +
                          " (against max), where no other row is at least as fast and as accurate and better in one; "
                          "an infinite error is never on it.");
    return table;
}

}  // namespace vri
