#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include "experiment_file_test.h"
#include "scoped_environment.h"
#include "libvri/core/simd_target.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_run.h"
#include "libvri/experiment/experiment_spec.h"
#include "libvri/experiment/gallery_grid.h"
#include "libvri/experiment/gallery.h"
#include "libvri/experiment/manifest.h"
#include "libvri/experiment/step_cache.h"
#include "libvri/util/error.h"

namespace fs = std::filesystem;

namespace {

// A scratch folder with two transfer functions, removed afterwards.
struct ExperimentDir {
    fs::path dir = fs::temp_directory_path() / ("vri-experiment-test-" + std::to_string(::getpid()));
    ExperimentDir() {
        fs::create_directories(dir);
        write("a.yaml", "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n");
        write("b.yaml", "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 0, 0, 0.5]\n");
    }
    ~ExperimentDir() { fs::remove_all(dir); }
    void write(const std::string& name, const std::string& text) const { std::ofstream(dir / name) << text; }
    vri::Experiment parse(const std::string& text, bool quick = false) const {
        return vri::parseExperiment(text, "exp.yaml", dir, quick);
    }
    std::string error(const std::string& text, bool quick = false) const {
        try {
            parse(text, quick);
        } catch (const vri::Error& e) {
            return e.what();
        }
        return "no error";
    }
};

const std::string kHead = "name: t\ntitle: T\npaper: {paper: A, item: Fig. 4, says: steps}\n";

const std::string kTwoScenes = kHead + R"(scenes:
  a: {field: linear, convention: node, tf: a.yaml, size: [8, 8]}
  b: {field: linear, convention: node, tf: b.yaml, size: [8, 8]}
methods:
  riemann:
    placement: [eye, entry]
    rate: 1
comparisons:
  ca: {reference: a-riemann-entry}
  cb: {reference: b-riemann-entry}
)";

std::vector<std::string> ids(const vri::Experiment& e) {
    std::vector<std::string> result;
    for (const vri::RunSpec& r : e.runs) result.push_back(r.id);
    return result;
}

}  // namespace

TEST_CASE("experiment: an unknown key is named with its line and column") {
    ExperimentDir d;
    const std::string text = kHead + "scenes:\n  s:\n    field: linear\n    convention: node\n    tf: a.yaml\n"
                                     "    colour: red\nmethods: {riemann: {rate: 1}}\n";
    CHECK(d.error(text).starts_with("exp.yaml:9:5: unknown key 'colour'"));
    CHECK(d.error(kHead + "scene: {}\n").starts_with("exp.yaml:4:1: unknown key 'scene'"));
    // Method parameters are checked against the run tool's list too.
    const std::string method = kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\n"
                                       "methods:\n  riemann: {rate: 1, stpe: 0.5}\n";
    CHECK(d.error(method).starts_with("exp.yaml:6:22: unknown key 'stpe'"));
}

TEST_CASE("experiment: a key given twice is named with both lines") {
    ExperimentDir d;
    CHECK(d.error(kTwoScenes + "methods:\n  composite: {rate: 1}\n")
              .starts_with("exp.yaml:14:1: duplicate key 'methods' (first at line 7)"));
    CHECK(d.error(kHead + "scenes:\n  s: {field: linear, convention: node, tf: a.yaml}\n  s: {field: linear}\n")
              .starts_with("exp.yaml:6:3: duplicate key 's' (first at line 5)"));
}

TEST_CASE("experiment: a wrong type or a bad value is named with its line and column") {
    ExperimentDir d;
    const std::string scene = "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\n";
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml, size: big}}\nmethods: {riemann: {}}\n")
              .starts_with("exp.yaml:4:65: size must be [width, height]"));
    CHECK(d.error(kHead + scene + "methods:\n  riemann: {step: [0.5, abc]}\n").starts_with("exp.yaml:6:25: step: expected a number > 0, got 'abc'"));
    CHECK(d.error(kHead + scene + "methods:\n  riemann: {step: -1}\n").starts_with("exp.yaml:6:19: step: expected a number > 0"));
    CHECK(d.error(kHead + scene + "methods:\n  riemann: {placement: middle}\n").starts_with("exp.yaml:6:24: placement"));
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: corner, tf: a.yaml}}\nmethods: {riemann: {}}\n")
              .starts_with("exp.yaml:4:41: convention"));
    CHECK(d.error(kHead + scene + "methods: {riemann: {}}\ncomparisons:\n  c: {reference: nope}\n")
              .starts_with("exp.yaml:7:18: unknown run 'nope'"));
    CHECK(d.error(kHead + scene + "methods: {riemann: {}}\nreproduce: {checks: [{of: riemann, metrics: [rmse]}]}\n")
              .starts_with("exp.yaml:6:45: metric 'rmse' does not apply to a run"));
    const std::string compare = kHead + scene + "methods: {riemann: {step: [0.5, 0.25]}}\ncomparisons:\n  c: ";
    CHECK(d.error(compare + "{reference: riemann-h0.25, diff_scale: 10}\n")
              .starts_with("exp.yaml:7:45: diff_scale needs diff_image"));
    CHECK(d.error(compare + "{reference: riemann-h0.25, diff_image: png, diff_scale: 0}\n")
              .starts_with("exp.yaml:7:62: diff_scale: expected a number > 0"));
    CHECK(d.error(compare + "{reference: riemann-h0.25, diff_image: exr, diff_scale: shared}\n")
              .starts_with("exp.yaml:7:62: diff_scale: shared is the scale of PNG heat maps (diff_image: png)"));
    CHECK(d.error(compare + "{reference: riemann-h0.25, diff_image: png, diff_scale: all}\n")
              .starts_with("exp.yaml:7:62: diff_scale"));
}

TEST_CASE("experiment: whole numbers written as YAML's int does not read them (099, 1e2) are taken") {
    // make fuzz found it: toDouble accepted size [099, 100], then as<int>() threw past every check.
    ExperimentDir d;
    const vri::Experiment e =
        d.parse(kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml, size: [099, 1e2]}}\n"
                        "methods: {riemann: {tiles: 02}}\n");
    CHECK(e.scenes[0].width == 99);
    CHECK(e.scenes[0].height == 100);
    CHECK(std::ranges::find(e.scenes[0].options, std::pair<std::string, std::string>("--size", "99x100")) !=
          e.scenes[0].options.end());
    CHECK(e.runs[0].tiles == 2);
}

TEST_CASE("experiment: a missing transfer function or volume is named with its line and column") {
    ExperimentDir d;
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: nope.yaml}}\nmethods: {riemann: {}}\n")
              .starts_with("exp.yaml:4:51: tf: no such file"));
    CHECK(d.error(kHead + "scenes: {s: {volume: v.raw, convention: cell, tf: a.yaml}}\nmethods: {riemann: {}}\n")
              .starts_with("exp.yaml:4:22: volume: no such file"));
    // A broken transfer function reports its own position.
    d.write("broken.yaml", "points:\n  - [0.5, 0, 0, 0, 0]\n  - [0.2, 0, 0, 0, 0]\n");
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: broken.yaml}}\nmethods: {riemann: {}}\n")
              .find("broken.yaml:3:5") != std::string::npos);
}

TEST_CASE("experiment: sweeps expand to the cartesian product with readable ids") {
    ExperimentDir d;
    const vri::Experiment e = d.parse(kHead + R"(scenes: {s: {field: linear, convention: node, tf: a.yaml}}
methods:
  riemann:
    placement: [eye, entry]
    step: [0.5, 0.25]
    precision: float
  fine: {method: composite, step: 0.1}
)");
    CHECK(ids(e) == std::vector<std::string>{"riemann-eye-h0.5", "riemann-eye-h0.25", "riemann-entry-h0.5",
                                             "riemann-entry-h0.25", "fine"});
    const vri::RunSpec& run = e.run("riemann-entry-h0.25");
    CHECK(run.options == vri::ToolOptions{{"--method", "riemann"}, {"--placement", "entry"}, {"--step", "0.25"},
                                          {"--precision", "float"}});
    CHECK(e.run("fine").options == vri::ToolOptions{{"--method", "composite"}, {"--step", "0.1"}});

    // With several scenes, ids start with the scene; a comparison covers the other runs of its scene.
    const vri::Experiment two = d.parse(kTwoScenes);
    CHECK(ids(two) == std::vector<std::string>{"a-riemann-eye", "a-riemann-entry", "b-riemann-eye", "b-riemann-entry"});
    REQUIRE(two.comparisons.size() == 2);
    CHECK(two.comparisons[0].id == "ca-a-riemann-eye");
    CHECK(two.comparisons[1].run == "b-riemann-eye");
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\nmethods:\n  riemann: {}\n"
                          "  other: {method: riemann}\n  riemann-x: {method: riemann}\n")
              .find("no error") != std::string::npos);
}

TEST_CASE("experiment: quick overrides merge maps and replace lists, ids stay") {
    ExperimentDir d;
    const std::string text = kHead + R"(scenes: {s: {field: linear, convention: node, tf: a.yaml, size: [500, 500]}}
methods:
  riemann: {placement: [eye, entry], step: [0.5, 0.1]}
quick:
  scenes: {s: {size: [50, 40]}}
  methods: {riemann: {step: [0.5]}}
)";
    const vri::Experiment full = d.parse(text), quick = d.parse(text, true);
    CHECK(full.runs.size() == 4);
    CHECK(ids(quick) == std::vector<std::string>{"riemann-eye-h0.5", "riemann-entry-h0.5"});
    const auto& options = quick.scenes[0].options;
    CHECK(std::find(options.begin(), options.end(), vri::ToolOption{"--size", "50x40"}) != options.end());
    CHECK(std::find(options.begin(), options.end(), vri::ToolOption{"--convention", "node"}) != options.end());
    CHECK(quick.quick);
    // A typo in the quick block is caught with its position, also when not running quick.
    CHECK(d.error(text + "  scene: {}\n").starts_with("exp.yaml:10:3: unknown key 'scene'"));
}

TEST_CASE("experiment: a changed transfer function changes the keys of its renders and what follows, nothing else") {
    ExperimentDir d;
    const vri::Experiment e = d.parse(kTwoScenes);
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    REQUIRE(plan.steps.size() == 6);
    CHECK(plan.dependencies[plan.steps.size() - 1].size() == 2);  // a diff depends on both renders

    vri::FileHasher before;
    const std::vector<std::string> keys = vri::stepKeys(plan, d.dir / "bin", before);
    vri::FileHasher again;
    CHECK(vri::stepKeys(plan, d.dir / "bin", again) == keys);  // stable
    // A forced SIMD target or way of loading voxels makes every step another run (its times and stats
    // differ), and only while set.
    for (const auto& [variable, value] : {std::pair{"VRI_SIMD_TARGET", "SCALAR"}, std::pair{"VRI_VOXEL_LOADS", "gather"}}) {
        if (std::getenv(variable)) continue;
        CAPTURE(variable);
        std::vector<std::string> withVariable;
        {
            const vri::test::ScopedEnvironment set(variable, std::string(value));
            vri::FileHasher forced;
            withVariable = vri::stepKeys(plan, d.dir / "bin", forced);
        }
        for (std::size_t i = 0; i < keys.size(); ++i) CHECK(withVariable[i] != keys[i]);
        vri::FileHasher unset;
        CHECK(vri::stepKeys(plan, d.dir / "bin", unset) == keys);
    }

    d.write("a.yaml", "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.6]\n");
    vri::FileHasher after;
    const std::vector<std::string> changed = vri::stepKeys(plan, d.dir / "bin", after);
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        const bool usesA = plan.steps[i].id.starts_with("a-") || plan.steps[i].id.starts_with("ca-");
        CAPTURE(plan.steps[i].id);
        CHECK((changed[i] != keys[i]) == usesA);
    }
}

TEST_CASE("experiment: commands name files relative to the directory they run from") {
    ExperimentDir d;
    const vri::Experiment e = d.parse(kTwoScenes);
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    const std::string line = vri::shellCommand(vri::commandWords(plan, plan.step("ca-a-riemann-eye"), d.dir / "bin"));
    CHECK(line == "bin/vri-diff results/t/a-riemann-entry.exr results/t/a-riemann-eye.exr --threshold 0.01,0.005,0.001 "
                  "--failpercent 100 --warnpercent 100 --json results/t/ca-a-riemann-eye.json");
    CHECK(plan.commandPath("/elsewhere/x.exr") == "/elsewhere/x.exr");
}

TEST_CASE("experiment: a command's options, flags, lists, inputs and outputs become its words") {
    ExperimentDir d;
    const std::string text = kHead + R"(commands:
  rays-node:
    tool: vri-rays2d
    options:
      convention: node
      rates: [1, 4, 16]
      fov: 30.0
      exact: true
      verbose: false
      label: "true"
      q: true
    inputs: {tf: a.yaml}
    outputs: {o: rays-node.csv, summary: errors-node.md}
quick:
  commands: {rays-node: {options: {rates: [1]}}}
)";
    const vri::Experiment e = d.parse(text);
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    const vri::Step& step = plan.step("rays-node");
    CHECK(step.kind == "command");
    // Scalars as the file spells them, a list joined, true a flag, false left out, a quoted "true" a word.
    CHECK(vri::shellCommand(vri::commandWords(plan, step, d.dir / "bin")) ==
          "bin/vri-rays2d --convention node --rates 1,4,16 --fov 30.0 --exact --label true -q --tf a.yaml "
          "-o results/t/rays-node.csv --summary results/t/errors-node.md");
    CHECK(step.inputs == std::vector<fs::path>{d.dir / "a.yaml"});
    CHECK(step.outputs == std::vector<fs::path>{plan.resultsDir / "rays-node.csv", plan.resultsDir / "errors-node.md"});
    CHECK(step.threads == 0);  // the tool's default
    CHECK(step.pixels == 0);

    // threads: and size: are what a Slurm job asks for, typed when the file is read.
    const std::string sized = kHead + "commands:\n  c: {tool: vri-rays2d, options: {threads: 3, size: 20x10}, outputs: {o: c.csv}}\n";
    const vri::Experiment s = d.parse(sized);
    const vri::Plan sizedPlan = vri::planExperiment(s, d.dir / "results" / s.name, d.dir);
    CHECK(sizedPlan.step("c").threads == 3);
    CHECK(sizedPlan.step("c").pixels == 200);

    // quick: merges into a command's options key by key.
    const vri::ToolOptions quick = d.parse(text, true).commands.at(0).options;
    CHECK(std::find(quick.begin(), quick.end(), vri::ToolOption{"--rates", "1"}) != quick.end());
    CHECK(std::find(quick.begin(), quick.end(), vri::ToolOption{"--convention", "node"}) != quick.end());

    // Its input files are hashed for the cache.
    vri::FileHasher before, after;
    const std::string key = vri::stepKeys(plan, d.dir / "bin", before).at(0);
    d.write("a.yaml", "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.6]\n");
    CHECK(vri::stepKeys(plan, d.dir / "bin", after).at(0) != key);
}

TEST_CASE("experiment: a mistake in a command is named with its line and column") {
    ExperimentDir d;
    const std::string head = kHead + "commands:\n  c:\n    tool: vri-rays2d\n";
    CHECK(d.error(head + "    output: {o: x.csv}\n").starts_with("exp.yaml:7:5: unknown key 'output'"));
    CHECK(d.error(head + "    outputs: {o: x.csv}\n    options: {rates: {a: 1}}\n")
              .starts_with("exp.yaml:8:22: option 'rates' must be a value, a list of values, true or false"));
    CHECK(d.error(head + "    outputs: {o: x.csv}\n    inputs: {tf: nope.yaml}\n")
              .starts_with("exp.yaml:8:18: input 'tf': no such file"));
    CHECK(d.error(head + "    outputs: {o: ../x.csv}\n").starts_with("exp.yaml:7:18: output 'o' must be a file name"));
    CHECK(d.error(head + "    outputs: {}\n").starts_with("exp.yaml:7:14: command 'c' has no outputs"));
    CHECK(d.error(head + "    outputs: {o: x.csv}\n    options: {threads: two}\n")
              .starts_with("exp.yaml:8:24: threads: expected"));
    CHECK(d.error(head + "    outputs: {o: x.csv}\n    options: {size: 10}\n").starts_with("exp.yaml:8:21: size: "));
    CHECK(d.error(kHead + "commands:\n  c: {tool: rays2d, outputs: {o: x.csv}}\n")
              .starts_with("exp.yaml:5:13: tool must be a vri tool"));
}

TEST_CASE("experiment: a figure reads files that other steps write, and runs after them") {
    ExperimentDir d;
    d.write("plot.yaml", "series: []\n");
    const std::string commands = kHead + "commands:\n  c: {tool: vri-rays2d, outputs: {o: rays.csv}}\n";
    CHECK(d.error(commands + "figures:\n  f: {spec: plot.yaml, data: [rays.csv, nope.csv]}\n")
              .starts_with("exp.yaml:7:30: figure 'f' reads 'nope.csv', which no step writes"));

    const vri::Experiment e = d.parse(commands + "figures:\n  f: {spec: plot.yaml, data: [rays.csv]}\n");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    REQUIRE(plan.steps.size() == 2);
    CHECK(plan.steps[1].id == "figure-f");
    CHECK(plan.dependencies[1] == std::vector<std::size_t>{0});
    // Data paths resolve against the results folder, which differs between full and quick runs.
    CHECK(vri::shellCommand(vri::commandWords(plan, plan.steps[1], d.dir / "bin")) ==
          "bin/vri-plot plot.yaml --data-dir results/t -o results/t/f.png");
}

TEST_CASE("experiment: the gallery shows images, then tables, then figures, commands' among them") {
    ExperimentDir d;
    d.write("plot.yaml", "series: []\n");
    const vri::Experiment e = d.parse(kHead + R"(scenes: {s: {field: linear, convention: node, tf: a.yaml}}
methods: {riemann: {}}
commands:
  c: {tool: vri-rays2d, outputs: {o: c.csv, summary: c.md, image: c.png}}
tables:
  time: {runs: [riemann]}
figures:
  f: {spec: plot.yaml, data: [c.csv, time.csv]}
)");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    fs::create_directories(plan.resultsDir);
    d.write("results/t/c.md", "| command table |\n");
    d.write("results/t/time.md", "| time table |\n");
    vri::FileHasher hasher;
    vri::writeManifest(e, plan, std::vector<vri::StepOutcome>(plan.steps.size()), d.dir / "bin", hasher);
    // A page a script wrote is listed by its heading after the experiments; a stale page of vri-run's (its
    // experiment gone) and one with an unsafe name are not.
    d.write("results/bricks-slurm.md", "What a script measured\n\n# Bricks | on [a] cluster\n\nIts table.\n");
    d.write("results/gone.md", "[Results](README.md) / gone\n## A removed experiment\n");
    d.write("results/x(y).md", "# Unsafe\n");
    const std::vector<vri::ScriptPage> scripts = vri::scriptPages(d.dir / "results");
    REQUIRE(scripts.size() == 1);
    CHECK(scripts.front().name == "bricks-slurm.md");
    CHECK(scripts.front().title == "Bricks on a cluster");
    const std::vector<vri::GalleryPage> pages = vri::galleryPages(vri::galleryEntries(d.dir / "results"), scripts);
    REQUIRE(pages.size() == 1);  // a short section stays on README.md
    CHECK(pages.front().name == "README.md");
    const std::string& md = pages.front().text;
    CHECK(md.find("| paper item | section | ours against the paper |") < md.find("(t/riemann.png)"));
    CHECK(md.find("| Paper A, Fig. 4 | [") <
          md.find("| written by a script | [Bricks on a cluster](bricks-slurm.md) | - |\n"));
    CHECK(md.find("| written by a script | [Bricks on a cluster](bricks-slurm.md) | - |\n") <
          md.find("(t/riemann.png)"));
    CHECK(md.find("gone.md") == std::string::npos);
    const std::vector<std::string> order{"(t/riemann.png)", "(t/c.png)", "| command table |", "| time table |",
                                         "(t/f.png)"};
    for (std::size_t i = 0; i + 1 < order.size(); ++i) {
        CAPTURE(order[i]);
        CHECK(md.find(order[i]) < md.find(order[i + 1]));
        CHECK(md.find(order[i + 1]) != std::string::npos);
    }
}

TEST_CASE("experiment: names are file names in the results folder, never paths, quotes or code") {
    CHECK(vri::isSafeName("paper-a-fig4"));
    CHECK(vri::isSafeName("Riemann_h0.5+x"));
    CHECK(vri::isSafeName("9"));
    for (const char* bad :
         {"", ".", "..", "a..b", ".hidden", "-x", "_x", "a/b", "a b", "it's", "x';system('touch X');x='", "$(touch X)",
          "`touch X`", "a\nb", "a\\b", "caf\u00e9", "a,b", "a\"b"}) {
        INFO(bad);
        CHECK_FALSE(vri::isSafeName(bad));
    }
    ExperimentDir d;
    const std::string head = "title: T\npaper: {paper: A, item: Fig. 4, says: steps}\n";
    const std::string command = "commands:\n  c: {tool: vri-rays2d, outputs: {o: x.csv}}\n";
    CHECK(d.error("name: \"..\"\n" + head + command).starts_with("exp.yaml:1:7: name must be letters, digits"));
    CHECK(d.error("name: \".\"\n" + head + command).starts_with("exp.yaml:1:7: name must be letters, digits"));
    CHECK(d.error("name: \"x';system('touch${IFS}X');x='\"\n" + head + command)
              .starts_with("exp.yaml:1:7: name must be"));
    CHECK(d.error(kHead + "commands:\n  \"../c\": {tool: vri-rays2d, outputs: {o: x.csv}}\n")
              .starts_with("exp.yaml:5:3: commands: a name must be letters, digits"));
    CHECK(d.error(kHead +
                  "commands:\n  c: {tool: vri-rays2d, outputs: {o: x.csv}}\nfigures:\n  \"f'g\": {spec: a.yaml}\n")
              .starts_with("exp.yaml:7:3: figures: a name must be"));
    CHECK(d.error(kHead + "scenes:\n  \"a b\": {field: linear, convention: node, tf: a.yaml, size: [8, 8]}\n"
                          "methods:\n  riemann: {placement: eye}\n")
              .starts_with("exp.yaml:5:3: scenes: a name must be"));
    CHECK(d.error(kHead + "scenes:\n  a: {field: linear, convention: node, tf: a.yaml, size: [8, 8]}\n"
                          "methods:\n  riemann: {placement: eye, backend: vulkan, device: [\"0\", \"../../x\"]}\n")
              .starts_with("exp.yaml:7:12: methods entry 'riemann': a swept value does not fit in a run id"));
}

TEST_CASE("experiment: a command writes only into the results folder, through outputs:") {
    ExperimentDir d;
    const std::string head = kHead + "commands:\n  c:\n    tool: vri-rays2d\n    outputs: {o: x.csv}\n";
    CHECK(d.error(head + "    options: {errors: ../outside.md}\n")
              .starts_with("exp.yaml:8:23: option 'errors' writes a file: name it under outputs:"));
    CHECK(d.error(head + "    options: {output: x.csv}\n").starts_with("exp.yaml:8:23: option 'output' writes a file"));
    CHECK(
        d.error(head + "    options: {rotation: ../x}\n").starts_with("exp.yaml:8:25: option 'rotation' names a file"));
    CHECK(d.error(head + "    options: {rotation: /tmp/x}\n")
              .starts_with("exp.yaml:8:25: option 'rotation' names a file"));
    CHECK(d.error(head + "    options: {rotation: out.csv}\n")
              .starts_with("exp.yaml:8:25: option 'rotation' names a file"));
    CHECK(d.error(head + "    options: {rotation: --csv}\n")
              .starts_with("exp.yaml:8:25: option 'rotation' names a file or an option"));
    CHECK(d.error(head + "    inputs: {o: a.yaml}\n")
              .starts_with("exp.yaml:8:17: input 'o' is an option that writes a file"));
    CHECK(d.error(kHead + "commands:\n  c: {tool: vri-run, outputs: {o: x.csv}}\n")
              .starts_with("exp.yaml:5:13: vri-run cannot be a command's tool"));
    CHECK(d.error(head + "    options: {rotation: -0.5, rates: [1, 4]}\n") == "no error");  // numbers are values

    // The plan holds every output in the experiment's folder, whatever made the Experiment.
    vri::Experiment e = d.parse(kHead + "commands:\n  c: {tool: vri-rays2d, outputs: {o: x.csv}}\n");
    e.commands[0].outputs[0].second = "../x.csv";
    CHECK_THROWS_WITH_AS(vri::planExperiment(e, d.dir / "results" / e.name, d.dir),
                         doctest::Contains("outside the experiment's folder"), vri::Error);
    e.commands[0].outputs[0].second = "x.csv";
    e.commands[0].name = "../c";
    CHECK_THROWS_WITH_AS(vri::planExperiment(e, d.dir / "results" / e.name, d.dir),
                         doctest::Contains("not a safe name"), vri::Error);
}

TEST_CASE("experiment: sweeps are counted against the run limit before they are expanded") {
    ExperimentDir d;
    std::string ten = "[1, 2, 3, 4, 5, 6, 7, 8, 9, 10]";
    const std::string scene = "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\nmethods:\n";
    // 10^4 runs are allowed; 10^8 are refused at once, without expanding them.
    CHECK(d.parse(kHead + scene + "  coupled: {h0: " + ten + ", eps: " + ten + ", h_max: " + ten + ", repeat: " + ten +
                  "}\n")
              .runs.size() == vri::kMaxRuns);
    CHECK(d.error(kHead + scene + "  coupled: {h0: " + ten + ", eps: " + ten + ", h_max: " + ten + ", repeat: " + ten +
                  ", warm_up: " + ten + ", h_min: " + ten + ", early_termination: [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, "
                  "0.7, 0.8, 0.9], accepted: [paper, richardson], device: [a, b, c, d, e]}\n") ==
          "exp.yaml:6:12: methods entry 'coupled': needs 100000000 runs, limit 10000");
    // The runs of earlier entries count too.
    CHECK(d.error(kHead + scene + "  coupled: {h0: " + ten + ", eps: " + ten + ", h_max: " + ten + ", repeat: " + ten +
                  "}\n  riemann: {step: 0.5}\n") ==
          "exp.yaml:7:12: methods entry 'riemann' with the 10000 runs before it: needs 10001 runs, limit 10000");
}

TEST_CASE("experiment: simd: on|off passes --simd and names swept runs") {
    ExperimentDir d;
    const vri::Experiment e = d.parse(kHead + R"(scenes: {s: {field: linear, convention: node, tf: a.yaml}}
methods:
  riemann: {precision: float, simd: [on, off]}
)");
    CHECK(ids(e) == std::vector<std::string>{"riemann-simd-on", "riemann-simd-off"});
    CHECK(e.run("riemann-simd-off").options ==
          vri::ToolOptions{{"--method", "riemann"}, {"--precision", "float"}, {"--simd", "off"}});
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\nmethods: {riemann: {simd: yes}}\n")
              .find("simd: unknown value 'yes' (expected on, off or a SIMD target") != std::string::npos);
    // `lower`: a run per SIMD target this CPU has below its best, named by the target.
    const vri::Experiment lower = d.parse(kHead + R"(scenes: {s: {field: linear, convention: node, tf: a.yaml}}
methods:
  riemann: {precision: float, simd: [on, lower]}
)");
    std::vector<std::string> expected{"riemann-simd-on"};
    const std::vector<std::string> targets = vri::availableSimdTargets();
    for (std::size_t i = 1; i < targets.size(); ++i) expected.push_back("riemann-simd-" + targets[i]);
    CHECK(ids(lower) == expected);
    CHECK(lower.run(expected.back()).options ==
          vri::ToolOptions{{"--method", "riemann"}, {"--precision", "float"}, {"--simd", targets.back()}});
}

TEST_CASE("experiment: tiles: N plans N bands with --region and a merge writing the run's own files") {
    ExperimentDir d;
    const std::string scene = "scenes: {s: {field: linear, convention: node, tf: a.yaml, size: [8, 5], png: {invert: true}}}\n";
    const vri::Experiment e = d.parse(kHead + scene + "methods:\n  riemann: {rate: [1, 2], tiles: 3}\n");
    CHECK(ids(e) == std::vector<std::string>{"riemann-r1", "riemann-r2"});  // tiles are not in the id
    CHECK(e.run("riemann-r1").tiles == 3);
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    std::vector<std::string> steps;
    for (const vri::Step& s : plan.steps) steps.push_back(s.id);
    CHECK(steps == std::vector<std::string>{"riemann-r1.tile-1", "riemann-r1.tile-2", "riemann-r1.tile-3", "riemann-r1",
                                            "riemann-r2.tile-1", "riemann-r2.tile-2", "riemann-r2.tile-3", "riemann-r2"});
    const vri::Step& tile = plan.step("riemann-r1.tile-2");
    CHECK(tile.tool == "vri-render");
    CHECK(vri::test::hasOption(tile.arguments, "--region", "0,1,8,2"));  // rows 5/3 .. 10/3
    CHECK(tile.pixels == 8 * 2);  // what its Slurm job's memory is sized by: the region's, not the image's
    CHECK(vri::test::hasOption(tile.arguments, "-o", "results/t/riemann-r1.tile-2.exr"));
    const vri::Step& merge = plan.step("riemann-r1");
    CHECK(merge.tool == "vri-merge-tiles");
    CHECK(merge.pixels == 8 * 5);  // it holds the whole image
    CHECK(vri::test::hasOption(merge.arguments, "--tile", "results/t/riemann-r1.tile-3.exr"));
    CHECK(std::ranges::find(merge.arguments, "--png-invert") != merge.arguments.end());
    // The untiled run's outputs, so that diffs, tables and figures read the same files.
    CHECK(merge.outputs == std::vector<fs::path>{d.dir / "results/t/riemann-r1.exr", d.dir / "results/t/riemann-r1.png",
                                                 d.dir / "results/t/riemann-r1.json"});
    CHECK(plan.dependencies[3] == std::vector<std::size_t>{0, 1, 2});

    const std::string methods = kHead + scene + "methods:\n  ";
    CHECK(d.error(methods + "riemann: {tiles: 0}\n") == "exp.yaml:6:20: tiles must be a whole number in 1..256, got 0");
    CHECK(d.error(methods + "riemann: {tiles: 2.5}\n").starts_with("exp.yaml:6:20: tiles must be a whole number"));
    CHECK(d.error(methods + "riemann: {tiles: [2, 3]}\n").starts_with("exp.yaml:6:20: tiles"));
    CHECK(d.error(methods + "riemann: {tiles: 6}\n") ==
          "exp.yaml:6:20: tiles: 6: more tiles than the 5 rows of scene 's' (a tile is a band of whole rows)");
    CHECK(d.error(methods + "coupled: {log_ray: '1,1', tiles: 2}\n") ==
          "exp.yaml:6:36: tiles: 2: log_ray logs one pixel: render it untiled");
    CHECK(d.error(methods + "exact: {max_error: 1e-6, tiles: 2}\n") ==
          "exp.yaml:6:35: tiles: 2: max_error searches a tolerance over the whole image; each tile would find its own: "
          "give the tolerance (eps) that an untiled max_error run records, or render untiled");
}

TEST_CASE("experiment: bricks of a raw file laid out by its name carry the bytes each brick holds") {
    ExperimentDir d;
    d.write("v_10x6x4_uint16.raw", std::string(10 * 6 * 4 * 2, '\0'));
    const std::string scene =
        "scenes: {s: {volume: v_10x6x4_uint16.raw, convention: cell, tf: a.yaml, size: [8, 5]}}\n";
    const vri::Experiment whole = d.parse(kHead + scene + "methods:\n  riemann: {step: 1}\n  simpson: {tiles: 2}\n");
    const vri::Plan wholePlan = vri::planExperiment(whole, d.dir / "results" / whole.name, d.dir);
    CHECK(wholePlan.step("riemann").volumeBytes == 10 * 6 * 4 * 2);         // the whole volume
    CHECK(wholePlan.step("simpson.tile-1").volumeBytes == 10 * 6 * 4 * 2);  // each tile loads all of it
    CHECK(wholePlan.step("simpson").volumeBytes == 0);                      // the merge holds images
    const vri::Experiment e = d.parse(kHead + scene + "methods:\n  riemann: {bricks: [2, 1, 1]}\n");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    // Brick 0 holds x 0..5 with the ghost layer x = 5, brick 1 x 5..9: 6 and 5 columns of 6 x 4 voxels, 2 bytes each.
    CHECK(plan.step("riemann.brick-0-0-0").volumeBytes == 6 * 6 * 4 * 2);
    CHECK(plan.step("riemann.brick-1-0-0").volumeBytes == 5 * 6 * 4 * 2);
    CHECK(plan.step("riemann").volumeBytes == 0);  // the join holds layers, not voxels
}

TEST_CASE("experiment: bricks in tiles: each brick's layer from its tiles, then the join") {
    ExperimentDir d;
    d.write("v_10x6x4_uint16.raw", std::string(10 * 6 * 4 * 2, '\0'));
    const vri::Experiment e =
        d.parse(kHead +
                "scenes: {s: {volume: v_10x6x4_uint16.raw, convention: cell, tf: a.yaml, size: [8, 5]}}\n"
                "methods:\n  riemann: {bricks: [2, 1, 1], tiles: 2}\n");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    for (const char* brick : {"riemann.brick-0-0-0", "riemann.brick-1-0-0"}) {
        const vri::Step& layer = plan.step(brick);
        CHECK(layer.tool == "vri-merge-tiles");  // the layer joined from the brick's tiles
        CHECK(std::ranges::count(layer.arguments, std::string("--tile")) == 2);
        for (const char* tile : {".tile-1", ".tile-2"}) {
            const vri::Step& t = plan.step(std::string(brick) + tile);
            CHECK(t.tool == "vri-render");
            CHECK(std::ranges::count(t.arguments, std::string("--region")) == 1);
            CHECK(std::ranges::count(t.arguments, std::string("--brick")) == 1);
        }
    }
    CHECK(plan.step("riemann.brick-0-0-0.tile-1").volumeBytes == 6 * 6 * 4 * 2);  // a tile of a brick holds the brick
    const vri::Step& join = plan.step("riemann");
    CHECK(std::ranges::count(join.arguments, std::string("--layer")) == 2);
    CHECK(plan.steps.size() == 2 * (2 + 1) + 1);
}

TEST_CASE("experiment: bricks of a NRRD whose voxels a brick reads by offset carry the bytes each brick holds") {
    ExperimentDir d;
    d.write("v.raw", std::string(10 * 6 * 4 * 2, '\0'));
    d.write("v.nhdr",
            "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 10 6 4\nendian: little\nencoding: raw\ndata file: v.raw\n\n");
    d.write("z.nrrd", "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 10 6 4\nendian: little\nencoding: gzip\n\n");
    const auto bricked = [&](const std::string& volume) {
        const vri::Experiment e =
            d.parse(kHead + "scenes: {s: {volume: " + volume +
                    ", convention: cell, tf: a.yaml, size: [8, 5]}}\nmethods:\n  riemann: {bricks: [2, 1, 1]}\n");
        return vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    };
    const vri::Plan nhdr = bricked("v.nhdr");
    // The header's data file keys the steps' cache with the header: a changed .raw reruns them.
    CHECK(std::ranges::count(nhdr.step("riemann.brick-0-0-0").inputs,
                             fs::absolute(d.dir / "v.raw").lexically_normal()) == 1);
    CHECK(nhdr.step("riemann.brick-0-0-0").volumeBytes == 6 * 6 * 4 * 2);  // as the raw file's bricks
    CHECK(nhdr.step("riemann.brick-1-0-0").volumeBytes == 5 * 6 * 4 * 2);
    // A gzip-encoded NRRD is read whole for a brick: no box to size it by (the planner falls back to the file).
    CHECK(bricked("z.nrrd").step("riemann.brick-0-0-0").volumeBytes == 0);
}

namespace {

// A baseline TIFF stack of `pages` pages of `w` x `h` uint16 zeros, uncompressed, a strip a page (as
// tests/tools/formats_tiff.sh writes them).
std::string tiffStack(int w, int h, int pages) {
    std::string file = "II*";
    file.push_back('\0');
    const auto put = [&file](std::uint32_t value, int bytes) {
        for (int b = 0; b < bytes; ++b) file.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
    };
    const std::uint32_t dataBytes = static_cast<std::uint32_t>(w * h * 2);
    put(8 + dataBytes, 4);  // the first page's directory, after its data
    for (int page = 0; page < pages; ++page) {
        const std::uint32_t data = static_cast<std::uint32_t>(file.size());
        file.append(dataBytes, '\0');
        put(10, 2);
        for (auto [tag, type, value] : std::initializer_list<std::array<std::uint32_t, 3>>{{256, 4, std::uint32_t(w)},
                                                                                           {257, 4, std::uint32_t(h)},
                                                                                           {258, 3, 16},
                                                                                           {259, 3, 1},
                                                                                           {262, 3, 1},
                                                                                           {273, 4, data},
                                                                                           {277, 3, 1},
                                                                                           {278, 4, std::uint32_t(h)},
                                                                                           {279, 4, dataBytes},
                                                                                           {339, 3, 1}}) {
            put(tag, 2);
            put(type, 2);
            put(1, 4);
            put(value, 4);
        }
        put(page + 1 < pages ? static_cast<std::uint32_t>(file.size()) + 4 + dataBytes : 0, 4);
    }
    return file;
}

}  // namespace

TEST_CASE("experiment: bricks of a TIFF stack, which a brick reads by its pages' rows, carry the bytes each holds") {
    ExperimentDir d;
    d.write("v.tif", tiffStack(10, 6, 4));
    const vri::Experiment e =
        d.parse(kHead +
                "scenes: {s: {volume: v.tif, convention: cell, tf: a.yaml, size: [8, 5]}}\nmethods:\n  riemann: "
                "{bricks: [2, 1, 1]}\n");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results" / e.name, d.dir);
    CHECK(plan.step("riemann.brick-0-0-0").volumeBytes == 6 * 6 * 4 * 2);  // as the raw file's bricks
    CHECK(plan.step("riemann.brick-1-0-0").volumeBytes == 5 * 6 * 4 * 2);
}

TEST_CASE("experiment: a comparison's id writes the run's scene once and the run's id whole") {
    CHECK(vri::comparisonId("vs-exact-bonsai", "bonsai-riemann-h0.5", "bonsai") == "vs-exact-bonsai-riemann-h0.5");
    CHECK(vri::comparisonId("vs-corner", "riemann-eye", "cube") == "vs-corner-riemann-eye");
    // A shared word that is not the scene stays twice: vs-exact of run exact-tol1e-4 must not read as a
    // comparison against "exact-tol".
    CHECK(vri::comparisonId("vs-exact", "exact-tol1e-4", "cube") == "vs-exact-exact-tol1e-4");
    CHECK(vri::comparisonId("vs-shader-bonsai-riemann", "bonsai-riemann-sampler", "bonsai") ==
          "vs-shader-bonsai-riemann-sampler");
    // The name keeps a word of its own: never the run's id.
    CHECK(vri::comparisonId("bonsai-riemann", "bonsai-riemann-sampler", "bonsai") == "bonsai-riemann-bonsai-riemann-sampler");
    CHECK(vri::comparisonId("vs-fine", "fine", "cube") == "vs-fine-fine");
    // A word that is only the start of the scene's name is not the scene.
    CHECK(vri::comparisonId("vs-bon", "bon-sai-riemann", "bon-sai") == "vs-bon-bon-sai-riemann");
    // Two comparisons that would write one file are refused, naming the comparison to rename.
    ExperimentDir d;
    CHECK(d.error(kHead + "scenes: {s: {field: linear, convention: node, tf: a.yaml}}\n"
                          "methods: {a: {method: riemann}, b-a: {method: riemann}, c: {method: riemann}}\n"
                          "comparisons:\n  vs-b: {reference: c, runs: [a]}\n  vs: {reference: c, runs: [b-a]}\n") ==
          "exp.yaml:8:7: comparison 'vs' of run 'b-a' has the id 'vs-b-a', which another run or comparison has "
          "(rename the comparison)");
}

TEST_CASE("experiment: the gallery's images are a scene-by-run matrix, a few columns a table") {
    std::vector<vri::GridImage> images;
    for (const char* scene : {"bonsai", "engine"})
        for (int h = 1; h <= 7; ++h) {
            const std::string run = "riemann-h" + std::to_string(h);
            images.push_back({std::string(scene) + "-" + run, "x/" + std::string(scene) + "-" + run + ".png", scene, run});
        }
    images.push_back({"bonsai-paper-ref", "x/bonsai-paper-ref.png", "bonsai", "paper-ref"});
    const std::string md = vri::imageGrid(images, "scene");
    CHECK(md.starts_with("| scene | riemann-h1 | riemann-h2 | riemann-h3 | riemann-h4 | riemann-h5 | riemann-h6 |\n"
                         "|:--|:-:|:-:|:-:|:-:|:-:|:-:|\n"
                         "| **bonsai** | ![bonsai-riemann-h1](x/bonsai-riemann-h1.png) |"));
    // The seventh run and the paper's reference start a second table; Engine has no reference: an empty cell.
    CHECK(md.find("\n\n| scene | riemann-h7 | paper-ref |\n|:--|:-:|:-:|\n"
                  "| **bonsai** | ![bonsai-riemann-h7](x/bonsai-riemann-h7.png) | "
                  "![bonsai-paper-ref](x/bonsai-paper-ref.png) |\n"
                  "| **engine** | ![engine-riemann-h7](x/engine-riemann-h7.png) | |\n\n") != std::string::npos);
    CHECK(std::ranges::count(md, '\n') == 2 + 2 + 2 + 2 + 2);  // two tables: heading, rule, two rows, a blank line
    CHECK(vri::imageGrid({}, "scene").empty());
}
