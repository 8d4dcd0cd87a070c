// The order of the experiments of one vri-run (plan_waves.h) and the data files a figure spec names
// (plot_data_files.h), by which a figure's step is keyed.
#include <doctest/doctest.h>

#include <fstream>

#include "libvri/experiment/plan_waves.h"
#include "libvri/io/plot_data_files.h"
#include "libvri/util/error.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

// A plan of one step that reads `inputs` and writes `outputs`.
vri::Plan plan(std::vector<fs::path> inputs, std::vector<fs::path> outputs) {
    vri::Plan p;
    p.steps.push_back({"s", "command", "vri-tf", {}, std::move(inputs), std::move(outputs), {}});
    p.dependencies.push_back({});
    return p;
}

}  // namespace

TEST_CASE("plan waves: a plan that reads another's outputs comes after it; others keep their order") {
    const std::vector<std::string> names{"a.yaml", "b.yaml", "c.yaml", "d.yaml"};
    // a reads b's x; c reads a's y; d reads a source only.
    const std::vector<vri::Plan> plans{plan({"/r/b/x.csv"}, {"/r/a/y.csv"}), plan({"/src/t.yaml"}, {"/r/b/x.csv"}),
                                       plan({"/r/a/../a/y.csv"}, {"/r/c/z.png"}), plan({"/src/t.yaml"}, {"/r/d/w"})};
    CHECK(vri::planWaves(plans, names) == std::vector<std::vector<std::size_t>>{{1, 3}, {0}, {2}});
    CHECK(vri::planWaves({plans[1], plans[3]}, {"b", "d"}) == std::vector<std::vector<std::size_t>>{{0, 1}});
    CHECK(vri::planWaves({}, {}).empty());
}

TEST_CASE("plan waves: plans that read each other's outputs are refused, naming both") {
    const std::vector<vri::Plan> cycle{plan({"/r/b/x"}, {"/r/a/y"}), plan({"/r/c/z"}, {"/r/b/x"}),
                                       plan({"/r/a/y"}, {"/r/c/z"})};
    CHECK_THROWS_WITH_AS(vri::planWaves(cycle, {"a.yaml", "b.yaml", "c.yaml"}),
                         doctest::Contains("a.yaml reads /r/b/x, which b.yaml writes"), vri::Error);
    // A plan that reads its own outputs (one step after another) is no cycle.
    CHECK(vri::planWaves({plan({"/r/a/y"}, {"/r/a/y"})}, {"a"}) == std::vector<std::vector<std::size_t>>{{0}});
}

TEST_CASE("plot data files: every series' file of one panel or of several, where vri-plot opens it") {
    const vri::test::TempDir dir("plot-data");
    std::ofstream(dir / "one.yaml")
        << "series:\n  - {file: a.csv, x: s, y: t}\n  - {file: ../other/b.csv, x: s, y: t}\n"
           "  - {file: a.csv, x: s, y: u}\n  - {file: /abs/c.csv, x: s, y: t}\n";
    CHECK(vri::plotDataFiles(dir / "one.yaml", "/results/exp") ==
          std::vector<fs::path>{"/results/exp/a.csv", "/results/other/b.csv", "/abs/c.csv"});
    std::ofstream(dir / "panels.yaml") << "panels:\n  - series: [{file: p.csv, x: a, y: b}]\n  - title: two\n"
                                          "    series: [{file: q.csv, x: a, y: b}, {x: a}]\n";
    CHECK(vri::plotDataFiles(dir / "panels.yaml", "/d") == std::vector<fs::path>{"/d/p.csv", "/d/q.csv"});
    std::ofstream(dir / "bad.yaml") << "series: [\n";
    CHECK_THROWS_WITH_AS(vri::plotDataFiles(dir / "bad.yaml", "/d"), doctest::Contains("bad.yaml:"), vri::Error);
    CHECK(vri::plotDataPath("x/../y.csv", "/d") == fs::path("/d/y.csv"));
}
