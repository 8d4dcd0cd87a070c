#include "libvri/report/plot_csv.h"

#include <algorithm>
#include <cmath>

#include "libvri/report/plot.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"

namespace vri::plot {

bool whereMatches(const std::string& text, const std::string& wanted) {
    if (wanted.ends_with('*')) return text.starts_with(std::string_view(wanted).substr(0, wanted.size() - 1));
    return text == wanted;
}

std::vector<std::vector<std::string>> keptRows(const PlotSeries& series) {
    std::vector<std::vector<std::string>> rows = readCsv(series.file).rows;
    std::erase_if(rows, [&](const std::vector<std::string>& row) {
        return !std::ranges::all_of(series.where, [&](const auto& condition) {
            const std::size_t column = condition.first - 1;
            return column < row.size() && whereMatches(row[column], condition.second);
        });
    });
    return rows;
}

namespace {

struct GridPoint {
    double x = 0, y = 0;
    std::array<std::string, 3> fields;  // x, y, z as written
};

std::vector<GridPoint> gridPoints(const std::filesystem::path& path, const CsvFile& csv,
                                  const std::array<int, 3>& columns) {
    std::vector<GridPoint> points;
    for (std::size_t r = 0; r < csv.rows.size(); ++r) {
        GridPoint point;
        std::array<double, 3> values{};
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t c = columns[i] - 1;
            point.fields[i] = c < csv.rows[r].size() ? csv.rows[r][c] : "";
            const auto value = parseNumber(point.fields[i]);
            // A value may be NaN (a blank cell), a place may not.
            if (!value || (i < 2 && !std::isfinite(*value)))
                throw Error(path.string() + ": data row " + std::to_string(r + 1) + ": " + csv.header[c] + " '" +
                            point.fields[i] + "' is not " + (i < 2 ? "a finite number" : "a number"));
            values[i] = *value;
        }
        point.x = values[0];
        point.y = values[1];
        points.push_back(point);
    }
    return points;
}

std::vector<double> distinct(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    return values;
}

// Evenly spaced to a thousandth of a step, as values rounded when written still are.
void requireEvenSpacing(const std::vector<double>& values, const std::filesystem::path& path,
                        const std::string& column) {
    const double step = (values.back() - values.front()) / static_cast<double>(values.size() - 1);
    for (std::size_t i = 1; i < values.size(); ++i)
        if (std::abs(values[i] - values[i - 1] - step) > 1e-3 * step)
            throw Error(path.string() + ": the values of " + column +
                        " are not evenly spaced, as those of a heatmap's grid must be");
}

}  // namespace

std::vector<std::array<std::string, 3>> gridRows(const std::filesystem::path& path, int xColumn, int yColumn,
                                                 int zColumn) {
    const CsvFile csv = readCsv(path);
    std::vector<GridPoint> points = gridPoints(path, csv, {xColumn, yColumn, zColumn});
    std::vector<double> xs, ys;
    for (const GridPoint& point : points) {
        xs.push_back(point.x);
        ys.push_back(point.y);
    }
    xs = distinct(xs);
    ys = distinct(ys);
    if (xs.size() < 2 || ys.size() < 2)
        throw Error(path.string() + ": a heatmap needs a grid of at least 2 x 2 points, this one is " +
                    std::to_string(xs.size()) + " x " + std::to_string(ys.size()));
    std::sort(points.begin(), points.end(),
              [](const GridPoint& a, const GridPoint& b) { return std::pair(a.y, a.x) < std::pair(b.y, b.x); });
    for (std::size_t i = 1; i < points.size(); ++i)
        if (points[i].x == points[i - 1].x && points[i].y == points[i - 1].y)
            throw Error(path.string() + ": the point (" + points[i].fields[0] + ", " + points[i].fields[1] +
                        ") is in more than one row");
    if (points.size() != xs.size() * ys.size())
        throw Error(path.string() + ": the points do not fill a grid: " + std::to_string(xs.size()) + " x values and " +
                    std::to_string(ys.size()) + " y values make " + std::to_string(xs.size() * ys.size()) +
                    " points, there are " + std::to_string(points.size()));
    requireEvenSpacing(xs, path, csv.header[xColumn - 1]);
    requireEvenSpacing(ys, path, csv.header[yColumn - 1]);
    std::vector<std::array<std::string, 3>> rows;
    for (const GridPoint& point : points) rows.push_back(point.fields);
    return rows;
}

}  // namespace vri::plot
