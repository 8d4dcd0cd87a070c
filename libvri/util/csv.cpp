#include "libvri/util/csv.h"

#include <cstdlib>
#include <fstream>

#include "libvri/util/error.h"

namespace vri {

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string csvLine(const std::vector<std::string>& fields) {
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i) line.append(i ? "," : "").append(csvField(fields[i]));
    return line + "\n";
}

std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += line[++i];
        else if (c == '"') quoted = !quoted;
        else if (c == ',' && !quoted) fields.emplace_back();
        else if (c != '\r') fields.back() += c;
    }
    return fields;
}

CsvFile readCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw Error(path.string() + ": no such file");
    CsvFile csv;
    std::string line;
    if (!std::getline(in, line) || line.empty()) throw Error(path.string() + ": empty, expected a header line");
    csv.header = splitCsvLine(line);
    while (std::getline(in, line))
        if (!line.empty()) csv.rows.push_back(splitCsvLine(line));
    return csv;
}

std::optional<double> parseNumber(const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) return std::nullopt;
    return value;
}

}  // namespace vri
