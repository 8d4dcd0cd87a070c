// Timing honesty: the runs a table times get a warm-up frame and the median of three unless the file says
// otherwise, listed as defaults; a timed table that rests on one frame is a warning.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "experiment_file_test.h"
#include "temp_dir.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"

namespace fs = std::filesystem;

namespace {

struct TimedDir {
    vri::test::TempDir temp{"timing-defaults"};
    const fs::path& dir = temp.path;
    TimedDir() { std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n"; }
    vri::Experiment parse(const std::string& methods) const {
        return vri::parseExperiment("name: t\nscenes: {s: {field: linear, tf: tf.yaml, size: [8, 6]}}\n"
                                    "references: {exact: {method: exact}}\nmethods:\n" + methods +
                                        "comparisons: {vs: {reference: exact}}\n"
                                        "tables: {speed: {layout: tradeoff, comparisons: [vs]}}\n",
                                    "t.yaml", dir, false);
    }
};

}  // namespace

TEST_CASE("timing defaults: a tabulated time is a warm-up frame and the median of three unless the file says") {
    TimedDir d;
    const vri::Experiment e = d.parse("  fast: {method: riemann, step: 1}\n  own: {method: riemann, step: 0.5, repeat: 5}\n");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/t", d.dir);
    CHECK(vri::test::hasOption(plan.step("fast").arguments, "--warm-up", "1"));
    CHECK(vri::test::hasOption(plan.step("fast").arguments, "--repeat", "3"));
    CHECK(vri::test::hasOption(plan.step("own").arguments, "--repeat", "5"));  // the file's own, kept
    CHECK(vri::test::hasOption(plan.step("own").arguments, "--warm-up", "1"));
    CHECK(!vri::test::hasOption(plan.step("exact").arguments, "--repeat", "3"));  // the reference is not timed
    CHECK(std::ranges::count(e.defaults, "run 'fast': warm_up 1 and repeat 3, as its time is tabulated") == 1);
    CHECK(std::ranges::count(e.defaults, "run 'own': warm_up 1, as its time is tabulated") == 1);
    CHECK(e.warnings.empty());

    const vri::Experiment once = d.parse("  fast: {method: riemann, step: [1, 0.5], repeat: 1}\n");
    CHECK(once.warnings == std::vector<std::string>{
                               "table 'speed' reports the time of 2 runs ('fast-h0.5', ...) from one frame (repeat: 1): "
                               "one sample, which varies by tens of % from run to run"});
}
