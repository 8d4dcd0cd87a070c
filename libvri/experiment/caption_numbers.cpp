// Captions whose numbers are read from the experiment's tables.
#include "libvri/experiment/caption_numbers.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/experiment/experiment_spec.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> splitAt(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1)
        parts.push_back(text.substr(start, at - start));
    parts.push_back(text.substr(start));
    return parts;
}

// The number at a dotted path of a JSON file (a part that is a number indexes an array): an integer
// as itself, any other number to 4 significant digits, as the tables print errors and times.
std::string jsonNumberText(const fs::path& file, const std::string& path, const std::string& cited) {
    return readingJsonOf(file, [&] {
        const nlohmann::json root = readJsonFile(file);
        const nlohmann::json* node = nullptr;
        try {
            node = &jsonAtPath(root, path, file);
        } catch (const Error& e) {
            throw Error(cited + ": " + e.what());
        }
        if (!node->is_number()) throw Error(cited + ": " + file.string() + ": '" + path + "' is not a number");
        if (node->is_number_integer()) return node->dump();
        char text[32];
        std::snprintf(text, sizeof text, "%.4g", node->get<double>());
        return std::string(text);
    });
}

}  // namespace

std::string fillCaptionNumbers(const std::string& text, const fs::path& folder) {
    std::map<std::string, CsvFile> tables;  // a table read once however often it is cited
    std::string out;
    std::size_t at = 0;
    for (std::size_t open; (open = text.find("{{", at)) != std::string::npos;) {
        out.append(text, at, open - at);
        const std::size_t close = text.find("}}", open + 2);
        if (close == std::string::npos) throw Error("caption: '" + text.substr(open, 40) + "': no closing }}");
        const std::string reference = text.substr(open + 2, close - open - 2);
        const std::string cited = "caption: {{" + reference + "}}";
        const std::vector<std::string> parts = splitAt(reference, ':');
        const bool isJson = parts.size() == 3 && parts[0] == "json";
        if (!(isJson || (parts.size() == 4 && parts[0] == "table")) ||
            std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
            throw Error(cited + ": expected {{table:NAME:ROW:COLUMN}} or {{json:NAME:PATH}}");
        if (!isSafeName(parts[1])) throw Error(cited + ": '" + parts[1] + "' is not a file name");
        if (isJson) {
            out += jsonNumberText(folder / (parts[1] + ".json"), parts[2], cited);
            at = close + 2;
            continue;
        }
        auto table = tables.find(parts[1]);
        const std::string file = (folder / (parts[1] + ".csv")).string();
        if (table == tables.end()) try {
                table = tables.emplace(parts[1], readCsv(file)).first;
            } catch (const Error& e) {
                throw Error(cited + ": " + e.what());
            }
        const CsvFile& csv = table->second;
        const auto column = std::find(csv.header.begin(), csv.header.end(), parts[3]);
        if (column == csv.header.end() || column == csv.header.begin())
            throw Error(cited + ": " + file + " has no column '" + parts[3] + "'");
        const auto row = std::find_if(csv.rows.begin(), csv.rows.end(),
                                      [&](const std::vector<std::string>& r) { return !r.empty() && r[0] == parts[2]; });
        if (row == csv.rows.end()) throw Error(cited + ": " + file + " has no row '" + parts[2] + "'");
        const std::size_t index = static_cast<std::size_t>(column - csv.header.begin());
        if (index >= row->size() || (*row)[index].empty())
            throw Error(cited + ": " + file + " has no value there");
        out += (*row)[index];
        at = close + 2;
    }
    out.append(text, at);
    return out;
}

}  // namespace vri
