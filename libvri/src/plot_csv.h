#pragma once
// Private: the little CSV reading that vri-plot needs (the header to find columns by name, the
// values for a Pareto front). Fields may be quoted as RFC 4180 says.
#include <filesystem>
#include <string>
#include <vector>

namespace vri::plot {

std::vector<std::string> splitCsvLine(const std::string& line);

struct CsvFile {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

// Throws vri::Error naming the file when it cannot be read or is empty.
CsvFile readCsv(const std::filesystem::path& path);

}  // namespace vri::plot
