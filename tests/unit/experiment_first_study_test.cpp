// A first own study without round trips: every missing required key in one error, no paper needed, the
// title and the grid convention filled in (and listed as defaults), volumes found in $VRI_DATA_DIR, and a
// dataset outside the repository's catalog pointing at volume: and VRI_DATA_DIR.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "experiment_file_test.h"
#include "scoped_environment.h"
#include "temp_dir.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"

namespace fs = std::filesystem;

namespace {

struct StudyDir {
    vri::test::TempDir temp{"first-study"};
    const fs::path& dir = temp.path;
    StudyDir() {
        fs::create_directories(dir / "data");
        std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n";
        std::ofstream(dir / "data" / "blob_4x4x4_uint8.raw") << std::string(64, '\x40');
    }
    vri::Experiment parse(const std::string& text) const { return vri::parseExperiment(text, "study.yaml", dir, false); }
    std::string error(const std::string& text) const { return vri::test::errorOf([&] { parse(text); }); }
};


}  // namespace

TEST_CASE("experiment files: every missing required key in one error") {
    StudyDir d;
    CHECK(d.error("scenes:\n  h: {size: [8, 8]}\n") ==
          "4 required keys missing: study.yaml:1:1: the experiment has no 'name'; study.yaml:1:1: the experiment "
          "has no 'methods'; study.yaml:2:6: scene 'h' has none of 'volume', 'dataset' or 'field'; study.yaml:2:6: "
          "scene 'h' has no 'tf'");
    CHECK(d.error("name: s\npaper: {paper: B}\nscenes: {h: {field: linear, tf: tf.yaml}}\nmethods: {r: {method: riemann}}\n") ==
          "2 required keys missing: study.yaml:2:8: paper has no 'item'; study.yaml:2:8: paper has no 'says'");
    CHECK(d.error("name: s\nscenes: {h: {field: linear, tf: tf.yaml}}\n") ==
          "study.yaml:1:1: the experiment has no 'methods'");
}

TEST_CASE("experiment files: an own study needs no paper, title or convention, and says what it assumed") {
    StudyDir d;
    const vri::Experiment e = d.parse("name: s\nscenes: {h: {field: linear, tf: tf.yaml, size: [8, 6]}}\n"
                                      "methods: {r: {method: riemann}}\n");
    CHECK(e.title == "study");
    CHECK(e.paper.paper == "none");
    CHECK(e.paper.item.empty());
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/s", d.dir);
    CHECK(vri::test::hasOption(plan.step("r").arguments, "--convention", "cell"));
    CHECK(e.defaults == std::vector<std::string>{"title: the file name 'study'", "paper: none (an own study)",
                                                 "scene 'h': convention cell, the tools' default"});
    // Given, nothing is a default.
    const vri::Experiment full = d.parse("name: s\ntitle: T\npaper: {paper: none}\n"
                                         "scenes: {h: {field: linear, convention: node, tf: tf.yaml}}\n"
                                         "methods: {r: {method: riemann}}\n");
    CHECK(full.defaults.empty());
}

TEST_CASE("experiment files: a volume is found beside the file, else in $VRI_DATA_DIR; a dataset says how") {
    StudyDir d;
    const std::string tail = ", tf: tf.yaml}}\nmethods: {r: {method: riemann}}\n";
    const vri::test::ScopedEnvironment data("VRI_DATA_DIR", (d.dir / "data").string());
    const vri::Experiment e = d.parse("name: s\nscenes: {h: {volume: blob_4x4x4_uint8.raw" + tail);
    CHECK(e.scenes[0].files[0] == d.dir / "data" / "blob_4x4x4_uint8.raw");
    const std::string missing = d.error("name: s\nscenes: {h: {volume: nope.raw" + tail);
    CHECK(missing.starts_with("study.yaml:2:22: volume: no such file: " + (d.dir / "nope.raw").string() + " nor " +
                              (d.dir / "data" / "nope.raw").string() + " ($VRI_DATA_DIR)"));
    const std::string dataset = d.error("name: s\nscenes: {h: {dataset: hydrogen_atom" + tail);
    CHECK(dataset.find("no catalog " + (d.dir / "datasets.yaml").string()) != std::string::npos);
    CHECK(dataset.find("volume: PATH") != std::string::npos);
    CHECK(dataset.find("$VRI_DATA_DIR") != std::string::npos);
}
