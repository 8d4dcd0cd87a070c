// vri-tabulate: the papers' tables (Markdown and CSV) from vri-diff and vri-render JSON files.
#include <CLI/CLI.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/render/tool_flags.h"
#include "libvri/report/convergence_table.h"
#include "libvri/report/table.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/parse.h"

namespace {

constexpr const char* kTool = "vri-tabulate";
// The most files one --row or --cell may name: a bound, so that a runaway word list is refused, not read.
constexpr int kMostFiles = 1 << 20;

struct Options {
    std::string layout;
    std::string markdown, csv, pointsCsv, title;
    std::optional<std::string> rowHeader;
    std::optional<int> precision;
    std::vector<double> thresholds;
    std::vector<double> tradeoffThresholds;
    std::string baseline, channels;
    std::vector<std::vector<std::string>> rows, cells, columnValues, columnPrecisions, runs, points;
    std::string value;
};

std::vector<std::filesystem::path> paths(std::vector<std::string>::const_iterator first,
                                         std::vector<std::string>::const_iterator last) {
    return {first, last};
}

// An option that one layout alone takes is a mistake with another.
void requireLayoutOptions(const Options& options) {
    const struct {
        const char* option;
        const char* layout;
        bool given;
    } owned[] = {
        {vri::tabulate_flag::row, "thresholds", !options.rows.empty()},
        {"--thresholds", "thresholds", !options.thresholds.empty()},
        {vri::tabulate_flag::cell, "matrix", !options.cells.empty()},
        {vri::tabulate_flag::value, "matrix", !options.value.empty()},
        {"--column-value", "matrix", !options.columnValues.empty()},
        {"--column-precision", "matrix", !options.columnPrecisions.empty()},
        {vri::tabulate_flag::run, "tradeoff", !options.runs.empty()},
        {vri::tabulate_flag::threshold, "tradeoff", !options.tradeoffThresholds.empty()},
        {vri::tabulate_flag::baseline, "tradeoff", !options.baseline.empty()},
        {vri::tabulate_flag::channels, "tradeoff", !options.channels.empty()},
        {vri::tabulate_flag::point, "convergence", !options.points.empty()},
        {vri::tabulate_flag::points, "convergence", !options.pointsCsv.empty()},
    };
    for (const auto& o : owned)
        if (o.given && options.layout != o.layout)
            throw vri::Error(std::string(o.option) + " belongs to --layout " + o.layout);
}

// --point SERIES H DIFF [STATS]; H is "-" for a run without a step.
std::vector<vri::ConvergencePoint> convergencePoints(const Options& options) {
    if (options.points.empty()) throw vri::Error("--layout convergence needs --point SERIES H DIFF [STATS]");
    std::vector<vri::ConvergencePoint> points;
    for (const auto& point : options.points) {
        std::optional<double> step;
        if (point[1] != "-") step = vri::parsePositive(point[1], "--point " + point[0] + ": step");
        points.push_back({point[0], step, point[2], point.size() == 4 ? point[3] : std::string()});
    }
    return points;
}

vri::Table buildTable(const Options& options) {
    requireLayoutOptions(options);
    if (options.layout == "convergence") return vri::convergenceTable(convergencePoints(options));
    if (options.layout == "thresholds") {
        if (options.rows.empty()) throw vri::Error("--layout thresholds needs --row LABEL FILE...");
        std::vector<vri::ThresholdRow> rows;
        for (const auto& row : options.rows) rows.push_back({row[0], paths(row.begin() + 1, row.end())});
        return vri::thresholdTable(rows, options.thresholds, options.precision);
    }
    if (options.layout == "tradeoff") {
        if (options.runs.empty()) throw vri::Error("--layout tradeoff needs --run LABEL STATS DIFF");
        std::vector<vri::TradeoffRow> rows;
        for (const auto& run : options.runs) rows.push_back({run[0], run[1], run[2]});
        vri::TradeoffOptions tradeoff;
        if (!options.tradeoffThresholds.empty()) tradeoff.thresholds = options.tradeoffThresholds;
        tradeoff.decimals = options.precision;
        tradeoff.baseline = options.baseline;
        tradeoff.perChannel = options.channels != "worst";
        return vri::tradeoffTable(rows, tradeoff);
    }
    if (options.cells.empty() || options.value.empty())
        throw vri::Error("--layout matrix needs --value EXPR and --cell ROW COLUMN FILE...");
    std::vector<vri::MatrixCell> cells;
    for (const auto& cell : options.cells) cells.push_back({cell[0], cell[1], paths(cell.begin() + 2, cell.end())});
    vri::MatrixOptions matrix;
    matrix.value = options.value;
    matrix.precision = options.precision.value_or(2);
    for (const auto& pair : options.columnValues) matrix.columnValue[pair[0]] = pair[1];
    for (const auto& pair : options.columnPrecisions)
        matrix.columnPrecision[pair[0]] = vri::parseCount(pair[1], "--column-precision " + pair[0], 0, 17);
    return vri::matrixTable(cells, matrix);
}

// The JSON files the table reads, each under the option that named it.
std::vector<vri::InputArgument> inputFiles(const Options& options) {
    std::vector<vri::InputArgument> inputs;
    const auto add = [&](const char* option, const std::vector<std::vector<std::string>>& groups, std::size_t first) {
        for (const auto& words : groups)
            for (std::size_t i = first; i < words.size(); ++i) inputs.push_back({option, words[i]});
    };
    add(vri::tabulate_flag::row, options.rows, 1);
    add(vri::tabulate_flag::cell, options.cells, 2);
    add(vri::tabulate_flag::run, options.runs, 1);
    add(vri::tabulate_flag::point, options.points, 2);
    return inputs;
}

int run(int argc, char** argv) {
    Options options;
    CLI::App app{"Builds a paper table from the JSON files vri-diff (--json) and vri-render (--stats) write: "
                 "Markdown, and CSV on request. Rows and columns keep the order given.",
                 kTool};
    app.add_option(vri::tabulate_flag::layout, options.layout,
                   "thresholds: % of rays above each threshold per channel (paper B Tables I, II, VI); "
                   "matrix: one value per row and column (Tables III-V); "
                   "tradeoff: per run its seconds per frame against its errors, with the Pareto front flagged; "
                   "convergence: per series of a step sweep its largest and mean error and their orders, the "
                   "slopes of log error against log h over the smallest steps")
        ->required()
        ->check(CLI::IsMember({"thresholds", "matrix", "tradeoff", "convergence"}));
    app.add_option("-o,--output", options.markdown, "Markdown table ('-' for stdout)")->required();
    app.add_option(vri::tabulate_flag::csv, options.csv, "also write the table as CSV");
    app.add_option(vri::tabulate_flag::title, options.title, "caption printed above the Markdown table");
    app.add_option("--row-header", options.rowHeader,
                   "heading of the label column (default: Method; run for tradeoff)");
    app.add_option(vri::tabulate_flag::precision, options.precision,
                   "decimals (default: 2 for matrix; thresholds and tradeoff's % columns have 3 significant digits)")
        ->check(vri::integerRange(0, 17));
    vri::addWordsOption(
        app, vri::tabulate_flag::row, options.rows, "LABEL FILE...", 2, kMostFiles,
        "thresholds: LABEL FILE [FILE...]; one vri-diff JSON for all thresholds, or one per threshold in "
        "threshold order");
    vri::addListOption(app, "--thresholds", options.thresholds,
                       "thresholds: which, comma separated (default: the first file's)");
    vri::addWordsOption(app, vri::tabulate_flag::cell, options.cells, "ROW COLUMN FILE...", 3, kMostFiles,
                        "matrix: ROW COLUMN FILE [FILE...]; several files give their median");
    app.add_option(vri::tabulate_flag::value, options.value,
                   "matrix: dotted JSON path of the value, e.g. stats.wall_seconds; "
                   "'1/PATH' for its reciprocal (fps)");
    vri::addWordsOption(app, "--column-value", options.columnValues, "COLUMN EXPR", 2, 2,
                        "matrix: COLUMN EXPR, another value for one column");
    vri::addWordsOption(app, "--column-precision", options.columnPrecisions, "COLUMN N", 2, 2,
                        "matrix: COLUMN N, other decimals for one column");
    vri::addWordsOption(app, vri::tabulate_flag::run, options.runs, "LABEL STATS DIFF", 3, 3,
                        "tradeoff: LABEL STATS DIFF, one row: the run's vri-render stats (timing.median_wall_seconds) "
                        "and its vri-diff JSON against the reference");
    vri::addWordsOption(app, vri::tabulate_flag::point, options.points, "SERIES H DIFF [STATS]", 3, 4,
                        "convergence: SERIES H DIFF [STATS], one run of a sweep: its step h in voxels ('-' for none), "
                        "its vri-diff JSON against the accurate reference and, for an error bound, its stats");
    app.add_option(vri::tabulate_flag::points, options.pointsCsv,
                   "convergence: also write the points as CSV (series,h,error,legend: the largest error; legend "
                   "holds the max order) for a log-log plot");
    vri::addListOption(app, vri::tabulate_flag::threshold, options.tradeoffThresholds,
                       "tradeoff: the error thresholds of the % columns, comma separated (default 0.001), each one the "
                       "diffs counted; the first is the % front's");
    app.add_option(vri::tabulate_flag::baseline, options.baseline,
                   "tradeoff: a run's LABEL; adds 'time ratio', every run's seconds over the baseline's");
    app.add_option(vri::tabulate_flag::channels, options.channels,
                   "tradeoff: all (default: % and max per channel and the worst) or worst (the worst channel only)")
        ->check(CLI::IsMember({"all", "worst"}));
    app.footer(
        "Labels may hold spaces (quote them). Markdown and CSV are written atomically; the Markdown ends with\n"
        "notes saying what the numbers are and, for medians, of how many runs.\n"
        "\n"
        "Examples:\n"
        "  vri-tabulate --layout thresholds --title 'Table I: % of rays above the error, Bonsai' \\\n"
        "      --row 'Riemann (h = 0.5)' riemann-0.5.diff.json \\\n"
        "      --row Coupled coupled-e0.01.diff.json coupled-e0.005.diff.json coupled-e0.001.diff.json \\\n"
        "      -o table1.md --csv table1.csv\n"
        "  vri-tabulate --layout matrix --value stats.wall_seconds --title 'Table III: CPU seconds per frame' \\\n"
        "      --cell 'Riemann h = 0.5' Bonsai run1.json run2.json run3.json \\\n"
        "      --cell 'Riemann h = 0.5' BluntFin run1b.json run2b.json run3b.json -o table3.md\n"
        "  vri-tabulate --layout matrix --value stats.wall_seconds --column-value 'GPU (fps)' 1/stats.wall_seconds \\\n"
        "      --column-precision 'GPU (fps)' 0 --cell Coupled 'CPU (s)' cpu.json --cell Coupled 'GPU (fps)' gpu.json -o -\n"
        "  vri-tabulate --layout tradeoff --threshold 0.001 --title 'Bonsai: seconds per frame against error' \\\n"
        "      --run riemann-h0.5 riemann-h0.5.json vs-exact-riemann-h0.5.json \\\n"
        "      --run simpson-e0.001 simpson-e0.001.json vs-exact-simpson-e0.001.json -o tradeoff.md --csv tradeoff.csv\n"
        "  vri-tabulate --layout tradeoff --threshold 0.001,0.01 --channels worst --baseline riemann-h0.5 \\\n"
        "      --run riemann-h0.5 riemann-h0.5.json vs-exact-riemann-h0.5.json \\\n"
        "      --run riemann-float-h0.5 riemann-float-h0.5.json vs-exact-riemann-float-h0.5.json -o bench.md\n"
        "  vri-tabulate --layout convergence --point riemann-eye 0.4 vs-exact-h0.4.json \\\n"
        "      --point riemann-eye 0.2 vs-exact-h0.2.json --point riemann-eye 0.1 vs-exact-h0.1.json \\\n"
        "      -o orders.md --points orders-points.csv");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    const std::vector<vri::OutputArgument> outputs{{"-o", options.markdown},
                                                   {vri::tabulate_flag::csv, options.csv},
                                                   {vri::tabulate_flag::points, options.pointsCsv}};
    vri::requireDistinctOutputs(outputs);
    vri::requireOutputsApartFromInputs(outputs, inputFiles(options));
    vri::Table table = buildTable(options);
    table.title = options.title;
    if (options.rowHeader) table.rowHeader = *options.rowHeader;
    const std::string markdown = vri::toMarkdown(table);
    const std::string csv = options.csv.empty() ? std::string() : vri::toCsv(table);
    const std::string points =
        options.pointsCsv.empty() ? std::string() : vri::convergencePointsCsv(convergencePoints(options));
    vri::OutputSet files;
    if (!options.csv.empty()) files.add(options.csv, csv);
    if (!options.pointsCsv.empty()) files.add(options.pointsCsv, points);
    files.add(options.markdown, markdown);
    files.write();
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
