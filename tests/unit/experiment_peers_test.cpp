// Peer renderers in experiment files: VTK's ray casters, like any outside renderer, are a `renderers:` entry whose
// command reads the card; a method with `renderer:` plans vri-outside with the card's options, the command after
// `--`, and the program's file as a cached input. The retired built-in peer methods are refused by name.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "experiment_file_test.h"
#include "temp_dir.h"
#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/experiment_spec.h"
#include "libvri/util/error.h"

namespace {

const std::string kPeersHead = R"(name: p
title: P
paper: {paper: none, item: peers, says: VTK as a peer}
scenes:
  s: {volume: v_2x2x2_uint8.raw, convention: cell, tf: tf.yaml, size: [8, 6], camera: {eye: [1, 1, -5], target: [1, 1, 1], fov: 30}}
)";

struct PeerDir {
    vri::test::TempDir dir{"experiment-peers"};
    PeerDir() {
        std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n";
        std::ofstream(dir / "v_2x2x2_uint8.raw") << "abcdefgh";
        // The adapter's place in the plan, not its run: planning looks the program up and digests it.
        std::ofstream(dir / "vri-peer-vtk") << "#!/bin/sh\n";
        std::filesystem::permissions(dir / "vri-peer-vtk", std::filesystem::perms::owner_all);
    }
    vri::Experiment parse(const std::string& rest) const {
        return vri::parseExperiment(kPeersHead + rest, "exp.yaml", dir.path, false);
    }
    std::string error(const std::string& rest) const {
        return vri::test::errorOf([&] { parse(rest); });
    }
};

using vri::test::hasOption;

}  // namespace

TEST_CASE("experiment files: VTK through its card is an outside renderer's run") {
    PeerDir d;
    const vri::Experiment e = d.parse(R"(renderers:
  vtk-cpu: {command: [./vri-peer-vtk, --card, "{card}", --method, vtk-fixed-point, -o, "{output}", --stats, "{stats}"]}
references:
  exact: {method: exact}
methods:
  vtk-cpu: {renderer: vtk-cpu, step: [2, 0.5]}
comparisons:
  vs: {reference: exact}
)");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/p", d.dir.path);
    const vri::Step& cpu = plan.step("vtk-cpu-h0.5");
    CHECK(cpu.tool == "vri-outside");
    CHECK(hasOption(cpu.arguments, "--step", "0.5"));
    CHECK(hasOption(cpu.arguments, "--eye", "1,1,-5"));
    CHECK(hasOption(cpu.arguments, "--renderer-name", "vtk-cpu"));
    const auto dashes = std::ranges::find(cpu.arguments, "--");
    REQUIRE(dashes != cpu.arguments.end());
    CHECK(dashes[1].ends_with("/vri-peer-vtk"));
    CHECK(std::ranges::find(cpu.arguments, "{card}") != cpu.arguments.end());  // filled in by vri-outside
    CHECK(std::ranges::any_of(cpu.inputs, [](auto& p) { return p.filename() == "vri-peer-vtk"; }));
    CHECK(std::ranges::any_of(cpu.outputs, [](auto& p) { return p.filename() == "vtk-cpu-h0.5.json"; }));
    CHECK(plan.step("vs-vtk-cpu-h2").tool == "vri-diff");  // compared like any render
}

TEST_CASE("experiment files: the built-in peer methods are gone, and a renderer's run stays whole") {
    PeerDir d;
    CHECK(d.error("methods:\n  v: {method: vtk-fixed-point}\n").find("vtk-fixed-point") != std::string::npos);
    const std::string renderer = "renderers:\n  r: {command: [./vri-peer-vtk, --card, \"{card}\"]}\n";
    CHECK(d.error(renderer + "methods:\n  v: {renderer: r, tiles: 2}\n").find("renders whole images only") !=
          std::string::npos);
    CHECK(d.error(renderer + "methods:\n  v: {renderer: r, method: exact}\n").find("not exact") != std::string::npos);
    CHECK(d.error(renderer + "references:\n  x: {renderer: r}\nmethods:\n  m: {step: 1}\n").find("renderer: belongs under methods") !=
          std::string::npos);
}
