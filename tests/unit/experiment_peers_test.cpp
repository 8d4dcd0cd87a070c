// Peer renderers in experiment files: `method: vtk-fixed-point` / `vtk-gpu` planned as vri-peer-vtk with the
// scene's options, the step swept like vri-render's, and what a peer cannot take refused with a place.
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

const std::string kPeersHead = R"(name: p
title: P
paper: {paper: none, item: peers, says: VTK as a peer}
scenes:
)";
const std::string kPeerScene = "  s: {volume: v_2x2x2_uint8.raw, convention: cell, tf: tf.yaml, size: [8, 6], "
                           "camera: {eye: [1, 1, -5], target: [1, 1, 1], fov: 30}}\n";

struct PeerDir {
    vri::test::TempDir dir{"experiment-peers"};
    PeerDir() {
        std::ofstream(dir / "tf.yaml") << "points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 0.5]\n";
        std::ofstream(dir / "v_2x2x2_uint8.raw") << "abcdefgh";
    }
    vri::Experiment parse(const std::string& scenes, const std::string& rest) const {
        return vri::parseExperiment(kPeersHead + scenes + rest, "exp.yaml", dir.path, false);
    }
    std::string error(const std::string& scenes, const std::string& rest) const {
        return vri::test::errorOf([&] { parse(scenes, rest); });
    }
};

using vri::test::hasOption;

}  // namespace

TEST_CASE("experiment files: a peer method runs vri-peer-vtk with the scene, its step and its outputs") {
    PeerDir d;
    const vri::Experiment e = d.parse(kPeerScene, R"(references:
  exact: {method: exact}
methods:
  vtk-cpu: {method: vtk-fixed-point, step: [2, 0.5], repeat: 3, warm_up: 1}
  vtk-gpu: {method: vtk-gpu, step: 1}
comparisons:
  vs: {reference: exact}
)");
    const vri::Plan plan = vri::planExperiment(e, d.dir / "results/p", d.dir.path);
    const vri::Step& cpu = plan.step("vtk-cpu-h0.5");
    CHECK(cpu.tool == "vri-peer-vtk");
    CHECK(hasOption(cpu.arguments, "--method", "vtk-fixed-point"));
    CHECK(hasOption(cpu.arguments, "--step", "0.5"));
    CHECK(hasOption(cpu.arguments, "--repeat", "3"));
    CHECK(hasOption(cpu.arguments, "--warm-up", "1"));
    CHECK(hasOption(cpu.arguments, "--eye", "1,1,-5"));
    CHECK(hasOption(cpu.arguments, "--size", "8x6"));
    CHECK(std::ranges::any_of(cpu.outputs, [](auto& p) { return p.filename() == "vtk-cpu-h0.5.json"; }));
    CHECK(plan.step("vtk-gpu").tool == "vri-peer-vtk");
    CHECK(hasOption(plan.step("vtk-gpu").arguments, "--method", "vtk-gpu"));
    CHECK(plan.step("vs-vtk-cpu-h2").tool == "vri-diff");  // compared like any render
}

TEST_CASE("experiment files: a peer refuses vri's method options and scenes it cannot render") {
    PeerDir d;
    CHECK(d.error(kPeerScene, "methods:\n  v: {method: vtk-gpu, eps: 0.01}\n")
              .find("eps does not apply to method vtk-gpu (vri-peer-vtk") != std::string::npos);
    CHECK(d.error(kPeerScene, "methods:\n  v: {method: vtk-fixed-point, placement: eye}\n").find("placement does not apply") !=
          std::string::npos);
    const std::string zoomed = "  s: {volume: v_2x2x2_uint8.raw, convention: cell, tf: tf.yaml, "
                               "camera: {eye: [1, 1, -5], target: [1, 1, 1], zoom: 2}}\n";
    CHECK(d.error(zoomed, "methods:\n  v: {method: vtk-fixed-point}\n").find("with --zoom") != std::string::npos);
    const std::string field = "  s: {field: linear, convention: node, tf: tf.yaml, camera: {eye: [1, 1, -5], "
                              "target: [0, 0, 0]}}\n";
    CHECK(d.error(field, "methods:\n  v: {method: vtk-fixed-point}\n").find("with --field") != std::string::npos);
    const std::string framed = "  s: {volume: v_2x2x2_uint8.raw, convention: cell, tf: tf.yaml}\n";
    CHECK(d.error(framed, "methods:\n  v: {method: vtk-gpu}\n").find("to set camera.eye") != std::string::npos);
    CHECK(d.error(kPeerScene, "methods:\n  v: {method: vtk-raycast}\n").find("vtk-raycast") != std::string::npos);
}
