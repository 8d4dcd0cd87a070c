#pragma once
// Reading the CSV files the tools write (a header line, then rows); fields may be quoted as
// RFC 4180 says.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vri {

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
