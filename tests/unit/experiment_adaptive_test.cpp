// Paper B in experiment files: the adaptive parameters and their run ids, `method: exact` planned as
// vri-reference, the per-ray log as an output, and threshold tables whose rows take one run per threshold.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "experiment_file_test.h"
#include "temp_dir.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"
#include "libvri/util/error.h"

namespace {

const std::string kScene = R"(name: b
title: B
paper: {paper: B, item: Table I, says: thresholds}
scenes:
  s: {field: linear, convention: node, tf: tf.yaml, size: [8, 8]}
)";

struct AdaptiveDir {
    vri::test::TempDir dir{"experiment-adaptive"};
    AdaptiveDir() { std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n"; }
    vri::Experiment parse(const std::string& rest) const {
        return vri::parseExperiment(kScene + rest, "exp.yaml", dir.path, false);
    }
    std::string error(const std::string& rest) const {
        return vri::test::errorOf([&] { parse(rest); });
    }
};

using vri::test::hasOption;

const std::string kRuns = R"(references:
  exact: {method: exact}
methods:
  riemann: {step: [0.5, 0.1]}
  coupled: {eps: [0.01, 0.001], h_min: 0.4, h_max: none, log_ray: "3,4"}
comparisons:
  vs: {reference: exact, thresholds: [0.01, 0.001]}
)";

}  // namespace

TEST_CASE("experiment files: adaptive parameters reach vri-render and swept ones name the run") {
    AdaptiveDir d;
    const vri::Experiment e = d.parse(kRuns);
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/b", d.dir.path);
    const vri::Step& coupled = plan.step("coupled-eps0.001");
    CHECK(coupled.tool == "vri-render");
    CHECK(hasOption(coupled.arguments, "--tolerance", "0.001"));
    CHECK(hasOption(coupled.arguments, "--h-min", "0.4"));
    CHECK(hasOption(coupled.arguments, "--h-max", "none"));
    CHECK(hasOption(coupled.arguments, "--log-ray", "3,4"));
    CHECK(std::ranges::any_of(coupled.outputs, [](auto& p) { return p.filename() == "coupled-eps0.001-ray.csv"; }));
    const vri::Step& exact = plan.step("exact");
    CHECK(exact.tool == "vri-reference");
    CHECK(hasOption(exact.arguments, "--method", "exact"));

    // The exact method as a timed method run: vri-reference at a tolerance, after a warm-up frame. Its eps is
    // a quadrature tolerance, no error level: the id says tol.
    const vri::Experiment timed = d.parse("references:\n  exact: {method: exact}\nmethods:\n"
                                          "  timed: {method: exact, eps: [1e-6, 1e-7], warm_up: 1, repeat: 5}\n");
    const vri::Plan timedPlan = vri::planExperiment(timed, d.dir / "results/b", d.dir.path);
    const vri::Step& loose = timedPlan.step("timed-tol1e-6");
    CHECK(loose.tool == "vri-reference");
    CHECK(hasOption(loose.arguments, "--tolerance", "1e-6"));
    CHECK(hasOption(loose.arguments, "--warm-up", "1"));
    CHECK(hasOption(loose.arguments, "--repeat", "5"));
}

TEST_CASE("experiment files: bad adaptive parameters and exact with method options are errors with a place") {
    AdaptiveDir d;
    CHECK(d.error("methods:\n  coupled: {eps: -1}\n").find("exp.yaml:7:") != std::string::npos);
    CHECK(d.error("methods:\n  coupled: {h_max: lots}\n").find("'none'") != std::string::npos);
    CHECK(d.error("methods:\n  coupled: {accepted: boole}\n").find("accepted") != std::string::npos);
    CHECK(d.error("methods:\n  coupled: {log_ray: \"1\"}\n").find("X,Y") != std::string::npos);
    CHECK(d.error("references:\n  exact: {method: exact, placement: eye}\nmethods: {r: {method: riemann}}\n").find("does not apply to method exact") !=
          std::string::npos);
    // vri-reference's own rule, checked when the file is read: its step belongs to its Riemann method.
    CHECK(d.error("references:\n  exact: {method: exact, step: 0.1}\nmethods: {r: {method: riemann}}\n").find("--step applies to --method riemann only") !=
          std::string::npos);
}

TEST_CASE("experiment tables: threshold rows take one run for all thresholds or one per threshold") {
    AdaptiveDir d;
    const vri::Experiment e = d.parse(kRuns + R"yaml(tables:
  t:
    comparisons: [vs]
    rows:
      "Riemann (h = 0.5)": [riemann-h0.5]
      Coupled: [coupled-eps0.01, coupled-eps0.001]
)yaml");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/b", d.dir.path);
    const vri::Step& table = plan.step("table-t");
    const auto& a = table.arguments;
    const auto row = std::ranges::find(a, "Coupled");
    REQUIRE(row != a.end());
    REQUIRE(a.end() - row >= 3);
    CHECK(row[1].ends_with("vs-coupled-eps0.01.json"));
    CHECK(row[2].ends_with("vs-coupled-eps0.001.json"));
    CHECK(std::ranges::count(a, "--row") == 2);

    const std::string tables = "tables:\n  t:\n    comparisons: [vs]\n    rows:\n";
    CHECK(d.error(kRuns + tables + "      C: [coupled-eps0.01, coupled-eps0.001, riemann-h0.1]\n").find("one per threshold") !=
          std::string::npos);
    CHECK(d.error(kRuns + tables + "      C: [nothing]\n").find("compared 0 times") != std::string::npos);
    CHECK(d.error(kRuns + "tables:\n  t:\n    layout: tradeoff\n    comparisons: [vs]\n    rows: {C: [riemann-h0.1]}\n")
              .find("rows applies to layout thresholds") != std::string::npos);
}
