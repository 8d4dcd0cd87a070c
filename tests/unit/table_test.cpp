// Tables from vri-diff and vri-render JSON: layouts, medians and the exact Markdown and CSV text.
#include <doctest/doctest.h>

#include <fstream>
#include <limits>

#include "temp_dir.h"
#include "libvri/report/table.h"
#include "libvri/util/error.h"
#include "libvri/util/statistics.h"

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
                                 {});
    table.title = "Table I";
    CHECK(toMarkdown(table) ==
          "**Table I**\n\n"
          "| Method | R > 0.01 | A > 0.01 | R > 0.001 | A > 0.001 |\n"
          "|:--|--:|--:|--:|--:|\n"
          "| Riemann (h = 0.5) | 10 | 11 | 10.1 | 11.1 |\n"
          "| Coupled | 1 | 2 | 2.1 | 3.1 |\n"
          "\n"
          "Percentage of rays (all pixels, background included) whose absolute error exceeds the threshold, "
          "per channel, to 3 significant digits (0: no ray).\n");
    CHECK(toCsv(table) ==
          "Method,R > 0.01,A > 0.01,R > 0.001,A > 0.001\n"
          "Riemann (h = 0.5),10,11,10.1,11.1\n"
          "Coupled,1,2,2.1,3.1\n");

    SUBCASE("a chosen subset of thresholds") {
        const Table only = thresholdTable({{"Riemann", {dir / "riemann.json"}}}, {0.001}, 2);
        CHECK(only.columns == std::vector<std::string>{"R > 0.001", "A > 0.001"});
        CHECK(toCsv(only) == "Method,R > 0.001,A > 0.001\nRiemann,10.10,11.10\n");
        CHECK(toMarkdown(only).ends_with("per channel, to 2 decimals.\n"));
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

TEST_CASE("table: significant digits fit numbers of any size, a percentage of 34.4375 reads 34.4") {
    Table table;
    table.rowHeader = "run";
    table.columns = {"worst > 0.001", "max"};
    table.precision = {kPercentDigits, 4};
    table.significant = {true, true};
    table.rows = {"a", "b", "c"};
    table.cells = {{34.4375, 0.107421875}, {0.000208333, 2.7e-7}, {0.0, 100.0}};
    CHECK(toCsv(table) == "run,worst > 0.001,max\na,34.4,0.1074\nb,0.000208,2.7e-07\nc,0,100\n");
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
        options.value = "stats.error_bound.max";  // a field of the schema this file lacks
        CHECK_THROWS_WITH_AS(matrixTable({{"a", "b", {dir / "r1.json"}}}, options),
                             doctest::Contains("r1.json: has no 'stats.error_bound'"), Error);
        options.value = "stats.missing";  // none of the schema's: refused before any file is read
        CHECK_THROWS_WITH_AS(matrixTable({{"a", "b", {dir / "nowhere.json"}}}, options),
                             doctest::Contains("'stats.missing' is no field of a render's stats"), Error);
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

namespace {

// A vri-diff JSON whose channels R and A were counted above 0.001 (and 0.01); a maximum may be null.
std::string tradeoffDiff(double percentR, double percentA, const std::string& maxR, const std::string& maxA) {
    auto channel = [](const char* name, double percent, const std::string& max) {
        return std::string("{\"name\": \"") + name + "\", \"max_abs\": " + max + ", \"rmse\": " + max + ", \"above\": [" +
               "{\"threshold\": 0.01, \"count\": 0, \"percent\": 0}, " +
               "{\"threshold\": 0.001, \"count\": 1, \"percent\": " + std::to_string(percent) + "}]}";
    };
    return "{\"thresholds\": [0.01, 0.001], \"pixels\": 100, \"channels\": [" + channel("R", percentR, maxR) + ", " +
           channel("A", percentA, maxA) + "]}";
}

// A run's stats: its median time per frame and its frames' times (default: one frame of that time), its
// method and, where it counts them, its samples evaluated.
std::string timingJson(double seconds, const std::string& options, const std::string& stats, std::string frames = "") {
    if (frames.empty()) frames = "[" + std::to_string(seconds) + "]";
    return "{\"timing\": {\"repeats\": 1, \"median_wall_seconds\": " + std::to_string(seconds) +
           ", \"wall_seconds\": " + frames + "}, \"options\": " + options + ", \"stats\": " + stats + "}";
}

}  // namespace

TEST_CASE("table: tradeoff layout, seconds against errors with the Pareto fronts flagged") {
    test::TempDir dir("table");
    std::vector<TradeoffRow> rows;
    const std::string riemann = R"({"method": "riemann", "precision": "double"})";
    const std::string cpu = R"({"backend": "cpu", "simd_target": null, "samples_evaluated": 4e6})";
    auto add = [&](const std::string& run, double seconds, double percentR, double percentA, const std::string& maxR,
                   const std::string& maxA, const std::string& options, const std::string& stats,
                   const std::string& frames = "") {
        writeFile(dir / (run + ".json"), timingJson(seconds, options, stats, frames));
        writeFile(dir / ("vs-" + run + ".json"), tradeoffDiff(percentR, percentA, maxR, maxA));
        rows.push_back({run, dir / (run + ".json"), dir / ("vs-" + run + ".json")});
    };
    add("riemann-h1", 0.1, 20, 10, "0.3", "0.2", riemann, cpu);
    add("riemann-h0.5", 0.2, 5, 1, "0.05", "0.1", riemann, cpu, "[0.26, 0.18, 0.2]");  // spread (0.26 - 0.18) / 0.2
    // slower than h0.5 with more rays above; float on the packets of rays
    add("riemann-h0.25", 0.4, 6, 1, "0.01", "0.001", R"({"method": "riemann", "precision": "float"})",
        R"({"backend": "cpu", "simd_target": "AVX2", "samples_evaluated": 4e6})");
    // as fast as h0.5, as many rays above: both on the % front; on the Vulkan backend
    add("simpson-e0.01", 0.2, 1, 5, "0.001", "0.0001", R"({"method": "coupled", "precision": "float"})",
        R"({"backend": "vulkan", "samples_evaluated": 4e6})");
    // an infinite error: never on the max front; vri-reference's stats count no samples, and bound the error
    add("exact", 0.3, 0, 0, "0.0001", "null", R"({"method": "exact", "precision": "double"})",
        R"({"error_bound": {"max": [1e-5, 2.5e-5, 1e-5, 1e-6]}})");
    TradeoffOptions twoDecimals;
    twoDecimals.decimals = 2;
    const Table table = tradeoffTable(rows, twoDecimals);
    CHECK(toCsv(table) ==
          "run,method,seconds,frames,spread %,ci low,ci high,Msamples/s,R > 0.001,A > 0.001,worst > 0.001,max R,"
          "max A,max,rmse,bound,pareto %,pareto max\n"
          "riemann-h1,riemann double,0.1,1,0,0.1,0.1,40,20.00,10.00,20.00,0.3,0.2,0.3,0.3,,1,1\n"
          "riemann-h0.5,riemann double,0.2,3,40,0.18,0.26,20,5.00,1.00,5.00,0.05,0.1,0.1,0.1,,1,0\n"
          "riemann-h0.25,riemann float SIMD,0.4,1,0,0.4,0.4,10,6.00,1.00,6.00,0.01,0.001,0.01,0.01,,0,0\n"
          "simpson-e0.01,coupled float vulkan,0.2,1,0,0.2,0.2,20,1.00,5.00,5.00,0.001,0.0001,0.001,0.001,,1,1\n"
          "exact,exact,0.3,1,0,0.3,0.3,,0.00,0.00,0.00,0.0001,inf,inf,inf,2.5e-05,1,0\n");
    const std::string markdown = toMarkdown(table);
    CHECK(markdown.starts_with("| run | method | seconds | frames | spread % | ci low | ci high | Msamples/s | "
                               "R > 0.001 | A > 0.001 | worst > 0.001 | max R | max A | max | rmse | bound | pareto % | "
                               "pareto max |\n"
                               "|:--|:--|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n"));
    CHECK(markdown.find("| exact | exact | 0.3 | 1 | 0 | 0.3 | 0.3 | - | ") != std::string::npos);
    CHECK(markdown.find("ci low, ci high: the frames' order statistics") != std::string::npos);
    CHECK(markdown.find("Warning:") == std::string::npos);  // no run's stats say it was timed under load
    CHECK(markdown.find("bound: the exact method's per-pixel error bound") != std::string::npos);
    CHECK(markdown.find("whose absolute error exceeds t (t = 0.001), to 2 decimals, per channel") != std::string::npos);
    CHECK(markdown.find("pareto % (pareto max): 1 on the Pareto front of seconds against worst > 0.001 (against max)") !=
          std::string::npos);

    SUBCASE("a single run is on both fronts; times and errors keep 4 significant digits, percentages 3") {
        add("alone", 1.23456, 0.5, 0.25, "1.234567e-07", "0", riemann, cpu);
        CHECK(toCsv(tradeoffTable({rows.back()})) ==
              "run,method,seconds,frames,spread %,ci low,ci high,Msamples/s,R > 0.001,A > 0.001,worst > 0.001,max R,"
              "max A,max,rmse,pareto %,pareto max\n"
              "alone,riemann double,1.235,1,0,1.235,1.235,3.24,0.5,0.25,0.5,1.235e-07,0,1.235e-07,1.235e-07,1,1\n");
    }
    SUBCASE("second-order pre-integration and jittered runs, one frame or the mean of several, are families of their own") {
        add("pre1", 1, 1, 1, "0.1", "0.1", R"({"method": "preintegrated", "precision": "double", "preint_order": 1})", cpu);
        add("pre2", 1, 1, 1, "0.1", "0.1", R"({"method": "preintegrated", "precision": "double", "preint_order": 2})", cpu);
        add("jit1", 1, 1, 1, "0.1", "0.1", R"({"method": "riemann", "precision": "double", "jitter": true, "frames": 1})", cpu);
        add("jit4", 1, 1, 1, "0.1", "0.1", R"({"method": "riemann", "precision": "double", "jitter": true, "frames": 4})", cpu);
        const Table table = tradeoffTable({rows.end() - 4, rows.end()});
        REQUIRE(table.texts.size() == 4);
        CHECK(table.texts[0][0] == "preintegrated double");
        CHECK(table.texts[1][0] == "preintegrated double order 2");
        CHECK(table.texts[2][0] == "riemann double jitter");
        CHECK(table.texts[3][0] == "riemann double jitter 4 frames");
    }
    SUBCASE("a benchmark's table: each time over the baseline's, two thresholds, the worst channel only") {
        TradeoffOptions options;
        options.thresholds = {0.001, 0.01};
        options.decimals = 1;
        options.baseline = "riemann-h0.5";
        options.perChannel = false;
        const Table bench = tradeoffTable(rows, options);
        CHECK(toCsv(bench) ==
              "run,method,seconds,frames,spread %,ci low,ci high,time ratio,Msamples/s,worst > 0.001,worst > 0.01,max,"
              "rmse,bound,"
              "pareto %,pareto max\n"
              "riemann-h1,riemann double,0.1,1,0,0.1,0.1,0.5,40,20.0,0.0,0.3,0.3,,1,1\n"
              "riemann-h0.5,riemann double,0.2,3,40,0.18,0.26,1,20,5.0,0.0,0.1,0.1,,1,0\n"
              "riemann-h0.25,riemann float SIMD,0.4,1,0,0.4,0.4,2,10,6.0,0.0,0.01,0.01,,0,0\n"
              "simpson-e0.01,coupled float vulkan,0.2,1,0,0.2,0.2,1,20,5.0,0.0,0.001,0.001,,1,1\n"
              "exact,exact,0.3,1,0,0.3,0.3,1.5,,0.0,0.0,inf,inf,2.5e-05,1,0\n");
        CHECK(toMarkdown(bench).find("time ratio: seconds over those of riemann-h0.5, timed in the same run.") !=
              std::string::npos);
        options.baseline = "riemann-h2";
        CHECK_THROWS_WITH_AS(tradeoffTable(rows, options),
                             doctest::Contains("baseline 'riemann-h2': no row of that name"), Error);
    }
    SUBCASE("errors name the file") {
        TradeoffOptions unknownThreshold;
        unknownThreshold.thresholds = {0.005};
        CHECK_THROWS_WITH_AS(tradeoffTable(rows, unknownThreshold),
                             doctest::Contains("vs-riemann-h1.json: no count above 0.005"), Error);
        writeFile(dir / "old.json", statsJson(1));
        CHECK_THROWS_WITH_AS(tradeoffTable({{"old", dir / "old.json", rows[0].diff}}),
                             doctest::Contains("old.json: has no 'timing'"), Error);
        writeFile(dir / "no-method.json", "{\"timing\": {\"median_wall_seconds\": 1}}");
        CHECK_THROWS_WITH_AS(tradeoffTable({{"no-method", dir / "no-method.json", rows[0].diff}}),
                             doctest::Contains("no-method.json: "), Error);
        writeFile(dir / "gray.json", "{\"channels\": [{\"name\": \"Y\", \"max_abs\": 0, \"above\": []}]}");
        rows.push_back({"gray", rows[0].stats, dir / "gray.json"});
        CHECK_THROWS_WITH_AS(tradeoffTable(rows), doctest::Contains("gray.json: its channels differ from those of"),
                             Error);
        CHECK_THROWS_WITH_AS(tradeoffTable({}), doctest::Contains("at least one row"), Error);
    }
}
