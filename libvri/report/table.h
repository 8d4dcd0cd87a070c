#pragma once
// The papers' tables, built from the JSON files the tools write (vri-diff --json, vri-render
// --stats) and printed as Markdown and CSV with the papers' number formats.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vri {

// Numbers with row and column labels. Cells without data are nullopt and print as "-" in
// Markdown, empty in CSV.
struct Table {
    std::string title;                // printed in bold above the Markdown table; not in the CSV
    std::string rowHeader;            // heading of the label column, e.g. "Method"
    // Columns of text after the label column, before the numbers (a run's method, say): their
    // headings, and per row one text each.
    std::vector<std::string> textColumns;
    std::vector<std::vector<std::string>> texts;  // [row][text column]; empty when there are none
    std::vector<std::string> columns;
    std::vector<std::string> rows;
    std::vector<std::vector<std::optional<double>>> cells;  // [row][column]
    std::vector<int> precision;       // decimals, per column
    // Per column, whether its precision counts significant digits instead ("34.4", "0.000208", "1.23e-05",
    // "0"): for numbers that span orders of magnitude, such as percentages of rays, maximum errors and
    // times. Empty: decimals everywhere.
    std::vector<bool> significant;
    std::vector<std::string> notes;   // lines under the Markdown table: what the numbers are
};

std::string toMarkdown(const Table& table);
std::string toCsv(const Table& table);

// Paper B Tables I, II and VI: one row per method, one column per threshold and channel
// ("R > 0.01", ...): the % of rays whose error exceeds the threshold, read from vri-diff JSON.
// A row takes one file for every threshold, or one file per threshold in threshold order (the
// adaptive methods are run at a tolerance that matches each threshold).
struct ThresholdRow {
    std::string label;
    std::vector<std::filesystem::path> files;
};
// `thresholds` empty: those of the first file. Throws vri::Error naming the file and what is
// missing when a file lacks a threshold or its channels differ from the first file's.
// The percentages have kPercentDigits significant digits, or `decimals` decimals when given.
inline constexpr int kPercentDigits = 3;
Table thresholdTable(const std::vector<ThresholdRow>& rows, std::vector<double> thresholds,
                     std::optional<int> decimals = std::nullopt);

// Paper B Tables III-V: rows and columns labelled freely (methods by datasets, or by backend),
// each cell one number read from JSON files; the median when a cell has several (runs repeated
// to steady a timing). Rows and columns keep the order of first appearance.
struct MatrixCell {
    std::string row;
    std::string column;
    std::vector<std::filesystem::path> files;
};
// A value expression: a dotted path into the JSON ("stats.wall_seconds", "channels.3.max_abs"),
// or "1/" and a path for its reciprocal (frames per second from seconds). With "1/" the cell is
// 1 / median, the median of the rates. JSON null (an infinite error in vri-diff) reads as +inf.
struct MatrixOptions {
    std::string value;                              // for every column not named below
    std::map<std::string, std::string> columnValue; // column label -> value expression
    int precision = 2;
    std::map<std::string, int> columnPrecision;     // column label -> decimals
};
// Throws vri::Error when a file lacks the value, a cell is given twice, or an override names no column.
Table matrixTable(const std::vector<MatrixCell>& cells, const MatrixOptions& options);

// Speed against accuracy (paper B's Riemann steps against adaptive tolerances): one row per compared
// run, its time per frame from its vri-render stats and its errors against the reference from the
// comparison's vri-diff JSON. Rows may come from several comparisons (one per method or backend).
struct TradeoffRow {
    std::string label;             // the run
    std::filesystem::path stats;   // vri-render --stats: timing.median_wall_seconds
    std::filesystem::path diff;    // vri-diff --json of the run against its reference
};
struct TradeoffOptions {
    std::vector<double> thresholds{0.001};  // the % columns, in this order; the first is the % front's
    std::optional<int> decimals;            // of the % columns; unset: kPercentDigits significant digits
    // A row's label, or empty: then a "time ratio" column gives each row's seconds over that row's,
    // a gain that reads the same on any machine when all rows were timed in one run.
    std::string baseline;
    bool perChannel = true;  // false: only the worst channel's % and the largest error, a compact table
};
// Columns: "method", text: the run's method family from its stats ("riemann float SIMD", "coupled
// double", "riemann float vulkan", "exact"), which a chart draws as one series; "seconds"; "time
// ratio" with a baseline; "Msamples/s", the samples evaluated per second in millions (empty where the
// stats count none, as vri-reference's); per threshold t "R > t", ... per channel and "worst > t", the
// largest of them: the % of rays whose error exceeds t (as `decimals` says); "max R", ... and "max":
// the largest absolute error per channel and of all; "rmse", the largest channel's root mean square
// error; "PSNR dB", "SSIM" and "FLIP", when any diff has metrics: its (image_metrics.h; empty where none);
// "pareto %" and "pareto max": 1 for the rows on the Pareto front of seconds against "worst > t"
// (the first threshold) or against "max" (see paretoFront), else 0. Throws vri::Error naming the file
// when a diff lacks a threshold or its channels differ from the first diff's, or when no row is the baseline.
Table tradeoffTable(const std::vector<TradeoffRow>& rows, const TradeoffOptions& options = {});

// A value expression applied to one JSON file: the number it names (see MatrixOptions).
double readJsonValue(const std::filesystem::path& file, const std::string& expression);

}  // namespace vri
