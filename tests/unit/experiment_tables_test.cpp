// The tables: of experiment files, chiefly the speed-against-accuracy layout (tradeoff): its keys,
// their errors with file:line:col, and the vri-tabulate step it plans.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "temp_dir.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"
#include "libvri/util/error.h"

namespace {

// Two step sweeps of Riemann sums and one composite run, each compared with a fine reference.
const std::string kExperiment = R"(name: t
title: T
paper: {paper: B, item: Table III, says: speed against accuracy}
scenes:
  s: {field: linear, convention: node, tf: tf.yaml, size: [8, 8]}
references:
  exact: {method: riemann, step: 0.01}
methods:
  riemann: {step: [1, 0.5]}
  fine: {method: composite, step: 0.25}
comparisons:
  vs-riemann: {reference: exact, runs: [riemann-h1, riemann-h0.5]}
  vs-fine: {reference: exact, runs: [fine], thresholds: [0.01, 1e-3]}
tables:
)";

struct TablesDir {
    vri::test::TempDir dir{"experiment-tables"};
    TablesDir() { std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n"; }
    vri::Experiment parse(const std::string& tables) const {
        return vri::parseExperiment(kExperiment + tables, "exp.yaml", dir.path, false);
    }
    std::string error(const std::string& tables) const {
        try {
            parse(tables);
        } catch (const vri::Error& e) {
            return e.what();
        }
        return "no error";
    }
};

}  // namespace

TEST_CASE("experiment tables: a tradeoff table takes rows from several comparisons, time from the runs' stats") {
    TablesDir d;
    const vri::Experiment e = d.parse("  speed:\n"
                                      "    layout: tradeoff\n"
                                      "    title: Speed\n"
                                      "    comparisons: [vs-riemann, vs-fine]\n"
                                      "    threshold: 0.001\n"
                                      "    precision: 2\n");
    REQUIRE(e.tables.size() == 1);
    CHECK(e.tables[0].layout == "tradeoff");
    CHECK(e.tables[0].thresholds == std::vector<std::string>{"0.001"});
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/t", d.dir.path);
    const vri::Step& step = plan.step("table-speed");
    const std::vector<std::string> expected{
        "--layout", "tradeoff", "--title", "Speed", "--threshold", "0.001",
        "--run", "riemann-h1", "results/t/riemann-h1.json", "results/t/vs-riemann-riemann-h1.json",
        "--run", "riemann-h0.5", "results/t/riemann-h0.5.json", "results/t/vs-riemann-riemann-h0.5.json",
        "--run", "fine", "results/t/fine.json", "results/t/vs-fine-fine.json",
        "--precision", "2", "-o", "results/t/speed.md", "--csv", "results/t/speed.csv"};
    CHECK(step.arguments == expected);
    // It runs after every render and comparison whose file it reads, so a new timing or error re-runs it.
    std::vector<std::string> after;
    const auto index = static_cast<std::size_t>(&step - plan.steps.data());
    for (std::size_t i : plan.dependencies[index]) after.push_back(plan.steps[i].id);
    std::sort(after.begin(), after.end());
    CHECK(after == std::vector<std::string>{"fine", "riemann-h0.5", "riemann-h1", "vs-fine-fine", "vs-riemann-riemann-h0.5",
                                            "vs-riemann-riemann-h1"});

    // Several thresholds, a baseline and the worst channel only reach vri-tabulate as its options.
    const vri::Experiment bench = d.parse("  speed: {layout: tradeoff, comparisons: [vs-riemann, vs-fine], "
                                          "threshold: [1e-3, 0.01], baseline: riemann-h1, channels: worst}\n");
    const vri::Plan benchPlan = vri::planExperiment(bench, d.dir / "results/t", d.dir.path);
    const std::vector<std::string>& words = benchPlan.step("table-speed").arguments;
    REQUIRE(words.size() > 10);
    const std::vector<std::string> head(words.begin(), words.begin() + 10);
    CHECK(head == std::vector<std::string>{"--layout", "tradeoff", "--title", "speed", "--threshold", "1e-3,0.01",
                                           "--baseline", "riemann-h1", "--channels", "worst"});

    // The threshold defaults to 0.001, and matches a comparison's threshold by value, not by spelling.
    const vri::Experiment plain = d.parse("  speed: {layout: tradeoff, comparisons: [vs-fine]}\n");
    CHECK(plain.tables[0].thresholds == std::vector<std::string>{"0.001"});
    // Without a layout, comparisons still make a threshold table and runs a table of values.
    const vri::Experiment implied = d.parse("  a: {comparisons: vs-fine}\n  b: {runs: fine}\n");
    CHECK(implied.tables[0].layout == "thresholds");
    CHECK(implied.tables[1].layout == "matrix");
}

TEST_CASE("experiment tables: wrong keys and values of a tradeoff table are named with their line and column") {
    TablesDir d;
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], treshold: 0.01}\n")
              .starts_with("exp.yaml:15:53: unknown key 'treshold'"));
    CHECK(d.error("  speed: {layout: pie, comparisons: [vs-fine]}\n") ==
          "exp.yaml:15:19: layout must be thresholds, matrix, tradeoff or convergence, got 'pie'");
    CHECK(d.error("  speed: {layout: tradeoff, runs: [fine]}\n") ==
          "exp.yaml:15:19: layout tradeoff takes comparisons, not runs");
    CHECK(d.error("  speed: {layout: matrix, comparisons: [vs-fine]}\n") ==
          "exp.yaml:15:19: layout matrix takes runs, not comparisons");
    CHECK(d.error("  orders: {layout: convergence, runs: [fine]}\n") ==
          "exp.yaml:15:20: layout convergence takes comparisons, not runs");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], threshold: [0.01, x]}\n") ==
          "exp.yaml:15:71: threshold must be a number");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], threshold: []}\n") ==
          "exp.yaml:15:64: threshold: an empty list");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], threshold: [0.01, 0.005]}\n") ==
          "exp.yaml:15:64: threshold 0.005 is not one that comparison 'vs-fine' counts (0.01, 1e-3)");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], baseline: riemann-h1}\n") ==
          "exp.yaml:15:63: baseline 'riemann-h1' is not a run of the table's comparisons");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], channels: some}\n") ==
          "exp.yaml:15:63: channels must be all or worst, got 'some'");
    CHECK(d.error("  speed: {comparisons: [vs-fine], baseline: fine}\n") ==
          "exp.yaml:15:45: baseline applies to layout tradeoff");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], threshold: -1}\n") ==
          "exp.yaml:15:64: threshold: expected a number >= 0, got '-1'");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-riemann, vs-fine], threshold: 0.005}\n") ==
          "exp.yaml:15:76: threshold 0.005 is not one that comparison 'vs-fine' counts (0.01, 1e-3)");
    CHECK(d.error("  speed: {comparisons: [vs-fine], threshold: 0.01}\n") ==
          "exp.yaml:15:46: threshold applies to layout tradeoff");
    CHECK(d.error("  speed: {layout: tradeoff, comparisons: [vs-fine], value: stats.wall_seconds}\n") ==
          "exp.yaml:15:60: value applies to a table of values (runs)");
}
