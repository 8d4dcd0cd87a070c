// Building the papers' tables, and the speed-against-accuracy table, from the JSON that vri-diff and
// vri-render write.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "vri/report/pareto.h"
#include "vri/report/table.h"
#include "vri/util/error.h"
#include "vri/util/json_file.h"
#include "vri/util/statistics.h"

namespace vri {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Follows a dotted path; a part that is a number indexes an array.
const json& lookup(const json& root, const std::string& path, const fs::path& file) {
    const json* node = &root;
    std::size_t start = 0;
    while (start <= path.size()) {
        const std::size_t end = std::min(path.find('.', start), path.size());
        const std::string part = path.substr(start, end - start);
        const bool isIndex = !part.empty() && std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
        if (node->is_array() && isIndex && std::stoul(part) < node->size()) node = &(*node)[std::stoul(part)];
        else if (node->is_object() && node->contains(part)) node = &(*node)[part];
        else throw Error(file.string() + ": has no '" + path.substr(0, end) + "'");
        start = end + 1;
    }
    return *node;
}

double numberAt(const json& root, const std::string& path, const fs::path& file) {
    const json& node = lookup(root, path, file);
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
    if (parsed.path.empty()) throw Error("value '" + expression + "': expected a dotted JSON path, e.g. stats.wall_seconds");
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
        for (const json& channel : lookup(diff, "channels", file)) names.push_back(channel.at("name").get<std::string>());
        return names;
    });
}

// The % of pixels whose error in `channel` exceeds `threshold`.
double percentAbove(const json& diff, std::size_t channel, double threshold, const fs::path& file) {
    const std::optional<double> percent = readingJsonOf(file, [&]() -> std::optional<double> {
        for (const json& above : lookup(diff, "channels." + std::to_string(channel) + ".above", file))
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

}  // namespace

double readJsonValue(const fs::path& file, const std::string& expression) {
    const ValueExpression parsed = parseExpression(expression);
    const double value = numberAt(readJsonFile(file), parsed.path, file);
    return parsed.reciprocal ? 1.0 / value : value;
}

Table thresholdTable(const std::vector<ThresholdRow>& rows, std::vector<double> thresholds, int precision) {
    if (rows.empty()) throw Error("a threshold table needs at least one row");
    const fs::path& first = rows.front().files.at(0);
    const json firstDiff = readJsonFile(first);
    if (thresholds.empty())
        readingJsonOf(first, [&] {
            for (const json& t : lookup(firstDiff, "thresholds", first)) thresholds.push_back(t.get<double>());
        });
    const std::vector<std::string> channels = channelNames(firstDiff, first);

    Table table;
    table.rowHeader = "Method";
    for (double threshold : thresholds)
        for (const std::string& channel : channels) {
            table.columns.push_back(channel + " > " + formatThreshold(threshold));
            table.precision.push_back(precision);
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
    table.notes.push_back("Percentage of rays (all pixels, background included) whose absolute error exceeds the "
                          "threshold, per channel.");
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
    return table;
}

Table tradeoffTable(const std::vector<TradeoffRow>& rows, double threshold, int precision) {
    if (rows.empty()) throw Error("a tradeoff table needs at least one row");
    const fs::path& first = rows.front().diff;
    const std::vector<std::string> channels = channelNames(readJsonFile(first), first);
    if (channels.empty()) throw Error(first.string() + ": has no channels");
    const std::string above = " > " + formatThreshold(threshold);
    constexpr int kDigits = 4;  // significant digits of times and maximum errors

    Table table;
    table.rowHeader = "run";
    auto addColumn = [&](const std::string& name, int digits, bool significant) {
        table.columns.push_back(name);
        table.precision.push_back(digits);
        table.significant.push_back(significant);
    };
    addColumn("seconds", kDigits, true);
    for (const std::string& channel : channels) addColumn(channel + above, precision, false);
    addColumn("worst" + above, precision, false);
    for (const std::string& channel : channels) addColumn("max " + channel, kDigits, true);
    addColumn("max", kDigits, true);
    addColumn("pareto %", 0, false);
    addColumn("pareto max", 0, false);

    std::vector<std::pair<double, double>> byPercent, byMax;  // (seconds, error) per row
    for (const TradeoffRow& row : rows) {
        const json diff = readJsonFile(row.diff);
        if (channelNames(diff, row.diff) != channels)
            throw Error(row.diff.string() + ": its channels differ from those of " + first.string());
        const double seconds = numberAt(readJsonFile(row.stats), "timing.median_wall_seconds", row.stats);
        table.rows.push_back(row.label);
        auto& cells = table.cells.emplace_back();
        cells.push_back(seconds);
        double worstPercent = 0, worstMax = 0;
        for (std::size_t c = 0; c < channels.size(); ++c) {
            cells.push_back(percentAbove(diff, c, threshold, row.diff));
            worstPercent = std::max(worstPercent, *cells.back());
        }
        cells.push_back(worstPercent);
        for (std::size_t c = 0; c < channels.size(); ++c) {
            cells.push_back(numberAt(diff, "channels." + std::to_string(c) + ".max_abs", row.diff));
            worstMax = std::max(worstMax, *cells.back());
        }
        cells.push_back(worstMax);
        byPercent.emplace_back(seconds, worstPercent);
        byMax.emplace_back(seconds, worstMax);
    }
    std::vector<double> onPercent(rows.size(), 0), onMax(rows.size(), 0);
    for (std::size_t r : paretoFront(byPercent)) onPercent[r] = 1;
    for (std::size_t r : paretoFront(byMax)) onMax[r] = 1;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        table.cells[r].push_back(onPercent[r]);
        table.cells[r].push_back(onMax[r]);
    }

    table.notes.push_back("seconds: median wall time per frame (the run's timing.median_wall_seconds).");
    table.notes.push_back(channels.front() + above + " ... worst" + above +
                          ": % of rays (all pixels, background included) whose absolute error exceeds " +
                          formatThreshold(threshold) + ", per channel and in the worst channel; max " +
                          channels.front() + " ... max: the largest absolute error, per channel and over all.");
    table.notes.push_back("pareto % (pareto max): 1 on the Pareto front of seconds against worst" + above +
                          " (against max), where no other row is at least as fast and as accurate and better in one; "
                          "an infinite error is never on it.");
    return table;
}

}  // namespace vri
