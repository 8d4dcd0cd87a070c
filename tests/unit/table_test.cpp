// Tables from vri-diff and vri-render JSON: layouts, medians and the exact Markdown and CSV text.
#include <doctest/doctest.h>

#include <fstream>
#include <limits>

#include "temp_dir.h"
#include "vri/error.h"
#include "vri/table.h"

using namespace vri;

namespace {

void writeFile(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// A vri-diff JSON with two channels and two thresholds; percents are base + channel + threshold index / 10.
std::string diffJson(double base) {
    auto channel = [&](const char* name, int c) {
        return std::string("{\"name\": \"") + name + "\", \"max_abs\": 0.5, \"above\": [" +
               "{\"threshold\": 0.01, \"count\": 1, \"percent\": " + std::to_string(base + c) + "}, " +
               "{\"threshold\": 0.001, \"count\": 2, \"percent\": " + std::to_string(base + c + 0.1) + "}]}";
    };
    return "{\"thresholds\": [0.01, 0.001], \"pixels\": 100, \"channels\": [" + channel("R", 0) + ", " +
           channel("A", 1) + "]}";
}

std::string statsJson(double seconds) {
    return "{\"stats\": {\"wall_seconds\": " + std::to_string(seconds) + ", \"rays\": 10}}";
}

}  // namespace

TEST_CASE("table: thresholds layout, one file per row or one per threshold") {
    test::TempDir dir("table");
    writeFile(dir / "riemann.json", diffJson(10));
    writeFile(dir / "coupled-0.01.json", diffJson(1));
    writeFile(dir / "coupled-0.001.json", diffJson(2));
    Table table = thresholdTable({{"Riemann (h = 0.5)", {dir / "riemann.json"}},
                                  {"Coupled", {dir / "coupled-0.01.json", dir / "coupled-0.001.json"}}},
                                 {}, 4);
    table.title = "Table I";
    CHECK(toMarkdown(table) ==
          "**Table I**\n\n"
          "| Method | R > 0.01 | A > 0.01 | R > 0.001 | A > 0.001 |\n"
          "|:--|--:|--:|--:|--:|\n"
          "| Riemann (h = 0.5) | 10.0000 | 11.0000 | 10.1000 | 11.1000 |\n"
          "| Coupled | 1.0000 | 2.0000 | 2.1000 | 3.1000 |\n"
          "\n"
          "Percentage of rays (all pixels, background included) whose absolute error exceeds the threshold, "
          "per channel.\n");
    CHECK(toCsv(table) ==
          "Method,R > 0.01,A > 0.01,R > 0.001,A > 0.001\n"
          "Riemann (h = 0.5),10.0000,11.0000,10.1000,11.1000\n"
          "Coupled,1.0000,2.0000,2.1000,3.1000\n");

    SUBCASE("a chosen subset of thresholds") {
        const Table only = thresholdTable({{"Riemann", {dir / "riemann.json"}}}, {0.001}, 2);
        CHECK(only.columns == std::vector<std::string>{"R > 0.001", "A > 0.001"});
        CHECK(toCsv(only) == "Method,R > 0.001,A > 0.001\nRiemann,10.10,11.10\n");
    }
    SUBCASE("errors name the file") {
        CHECK_THROWS_WITH_AS(thresholdTable({{"x", {dir / "riemann.json"}}}, {0.5}, 4),
                             doctest::Contains("riemann.json: no count above 0.5"), Error);
        CHECK_THROWS_WITH_AS(thresholdTable({{"x", {dir / "missing.json"}}}, {}, 4),
                             doctest::Contains("missing.json: no such file"), Error);
        CHECK_THROWS_WITH_AS(
            thresholdTable({{"x", {dir / "riemann.json", dir / "riemann.json", dir / "riemann.json"}}}, {}, 4),
            doctest::Contains("expected 1 or one per threshold (2)"), Error);
    }
}

TEST_CASE("table: matrix layout takes the median of several runs") {
    test::TempDir dir("table");
    writeFile(dir / "r1.json", statsJson(3.0));
    writeFile(dir / "r2.json", statsJson(1.0));
    writeFile(dir / "r3.json", statsJson(2.0));
    writeFile(dir / "c1.json", statsJson(0.5));
    MatrixOptions options;
    options.value = "stats.wall_seconds";
    Table table = matrixTable({{"Riemann h = 0.5", "Bonsai", {dir / "r1.json", dir / "r2.json", dir / "r3.json"}},
                               {"Coupled", "Bonsai", {dir / "c1.json"}},
                               {"Coupled", "Engine, CPU", {dir / "c1.json"}}},
                              options);
    CHECK(toMarkdown(table) ==
          "| Method | Bonsai | Engine, CPU |\n"
          "|:--|--:|--:|\n"
          "| Riemann h = 0.5 | 2.00 | - |\n"
          "| Coupled | 0.50 | 0.50 |\n"
          "\n"
          "Values: stats.wall_seconds.\n"
          "Each cell is the median of 1 to 3 runs.\n");
    CHECK(toCsv(table) == "Method,Bonsai,\"Engine, CPU\"\nRiemann h = 0.5,2.00,\nCoupled,0.50,0.50\n");

    SUBCASE("a column in frames per second, with its own decimals") {
        options.columnValue["Bonsai"] = "1/stats.wall_seconds";
        options.columnPrecision["Bonsai"] = 0;
        const Table fps = matrixTable({{"Riemann", "Bonsai", {dir / "r1.json", dir / "c1.json"}}}, options);
        CHECK(toCsv(fps) == "Method,Bonsai\nRiemann,1\n");  // 1 / median(3, 0.5) = 1 / 1.75
    }
    SUBCASE("errors") {
        CHECK_THROWS_WITH_AS(matrixTable({{"a", "b", {dir / "r1.json"}}, {"a", "b", {dir / "r2.json"}}}, options),
                             doctest::Contains("given twice"), Error);
        options.value = "stats.missing";
        CHECK_THROWS_WITH_AS(matrixTable({{"a", "b", {dir / "r1.json"}}}, options),
                             doctest::Contains("r1.json: has no 'stats.missing'"), Error);
    }
}

TEST_CASE("table: median, JSON paths with array indices, Markdown escaping") {
    CHECK(median({3, 1, 2}) == 2);
    CHECK(median({4, 1, 2, 3}) == 2.5);
    CHECK_THROWS_AS(median({}), Error);

    test::TempDir dir("table");
    writeFile(dir / "d.json", diffJson(0));
    CHECK(readJsonValue(dir / "d.json", "channels.1.above.0.percent") == 1.0);
    CHECK(readJsonValue(dir / "d.json", "1/channels.0.max_abs") == 2.0);
    writeFile(dir / "inf.json", "{\"max_abs\": null}");
    CHECK(readJsonValue(dir / "inf.json", "max_abs") == std::numeric_limits<double>::infinity());

    Table table;
    table.rowHeader = "a|b";
    table.columns = {"x"};
    table.rows = {"r"};
    table.cells = {{std::nullopt}};
    table.precision = {1};
    CHECK(toMarkdown(table) == "| a\\|b | x |\n|:--|--:|\n| r | - |\n");
}
