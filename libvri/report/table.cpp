// Printing tables as Markdown and CSV, with a fixed number of decimals or significant digits per column.
#include "libvri/report/table.h"

#include <algorithm>
#include <cstdio>

#include "libvri/util/csv.h"
#include "libvri/util/error.h"

namespace vri {

namespace {

std::string formatNumber(const Table& table, std::size_t column, const std::optional<double>& value,
                         const char* missing) {
    if (!value) return missing;
    const bool significant = !table.significant.empty() && table.significant[column];
    char text[64];
    std::snprintf(text, sizeof text, significant ? "%.*g" : "%.*f", table.precision[column], *value);
    return text;
}

// A pipe inside a cell would end it.
std::string markdownCell(const std::string& text) {
    std::string escaped;
    for (char c : text) {
        if (c == '|') escaped += '\\';
        escaped += c == '\n' ? ' ' : c;
    }
    return escaped;
}

void requireConsistent(const Table& table) {
    if (table.cells.size() != table.rows.size() || table.precision.size() != table.columns.size() ||
        (!table.significant.empty() && table.significant.size() != table.columns.size()) ||
        (!table.textColumns.empty() && table.texts.size() != table.rows.size()))
        throw Error("table '" + table.title + "': rows, columns and cells disagree in size");
    for (const auto& row : table.texts)
        if (row.size() != table.textColumns.size())
            throw Error("table '" + table.title + "': a row has the wrong number of texts");
    for (const auto& row : table.cells)
        if (row.size() != table.columns.size())
            throw Error("table '" + table.title + "': a row has the wrong number of cells");
}

}  // namespace

std::string toMarkdown(const Table& table) {
    requireConsistent(table);
    std::string out;
    if (!table.title.empty()) out += "**" + markdownCell(table.title) + "**\n\n";
    out += "| " + markdownCell(table.rowHeader) + " |";
    for (const std::string& column : table.textColumns) out.append(" ").append(markdownCell(column)).append(" |");
    for (const std::string& column : table.columns) out.append(" ").append(markdownCell(column)).append(" |");
    out += "\n|:--|";
    for (std::size_t c = 0; c < table.textColumns.size(); ++c) out += ":--|";
    for (std::size_t c = 0; c < table.columns.size(); ++c) out += "--:|";
    out += "\n";
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        out += "| " + markdownCell(table.rows[r]) + " |";
        if (!table.textColumns.empty())
            for (const std::string& text : table.texts[r]) out.append(" ").append(markdownCell(text)).append(" |");
        for (std::size_t c = 0; c < table.columns.size(); ++c)
            out.append(" ").append(formatNumber(table, c, table.cells[r][c], "-")).append(" |");
        out += "\n";
    }
    if (!table.notes.empty()) out += "\n";
    for (const std::string& note : table.notes) out += note + "\n";
    return out;
}

std::string toCsv(const Table& table) {
    requireConsistent(table);
    std::string out = csvField(table.rowHeader);
    for (const std::string& column : table.textColumns) out.append(",").append(csvField(column));
    for (const std::string& column : table.columns) out.append(",").append(csvField(column));
    out += "\n";
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        out += csvField(table.rows[r]);
        if (!table.textColumns.empty())
            for (const std::string& text : table.texts[r]) out.append(",").append(csvField(text));
        for (std::size_t c = 0; c < table.columns.size(); ++c)
            out.append(",").append(formatNumber(table, c, table.cells[r][c], ""));
        out += "\n";
    }
    return out;
}

}  // namespace vri
