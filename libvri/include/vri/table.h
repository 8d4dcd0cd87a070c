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
    std::vector<std::string> columns;
    std::vector<std::string> rows;
    std::vector<std::vector<std::optional<double>>> cells;  // [row][column]
    std::vector<int> precision;       // decimals, per column
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
Table thresholdTable(const std::vector<ThresholdRow>& rows, std::vector<double> thresholds, int precision = 4);

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

// Median of a non-empty list: the middle value, or the mean of the two middle ones.
double median(std::vector<double> values);

// A value expression applied to one JSON file: the number it names (see MatrixOptions).
double readJsonValue(const std::filesystem::path& file, const std::string& expression);

}  // namespace vri
