#pragma once
// The CSV files the tools write and read: a header line, then rows; fields quoted as RFC 4180 says.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vri {

// A field as written: quoted when it holds a comma, quote or line break, quotes doubled.
std::string csvField(const std::string& text);
// One line of fields, with its newline.
std::string csvLine(const std::vector<std::string>& fields);

std::vector<std::string> splitCsvLine(const std::string& line);

struct CsvFile {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

// Throws vri::Error naming the file when it cannot be read or is empty.
CsvFile readCsv(const std::filesystem::path& path);

// The number a field holds, when it holds a number and nothing else.
std::optional<double> parseNumber(const std::string& text);

}  // namespace vri
