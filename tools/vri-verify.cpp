// vri-verify: a renderer's verification report against vri's certified reference, for a CI job.
#include "common/render_main.h"

namespace {

constexpr vri::RenderCommandHelp kHelp{
    "Verify a renderer: run it (the command after --) on vri's scene cards at a sweep of steps, compare each "
    "image with vri's exact reference, and report the observed order of convergence, the error floor, the "
    "sample placement it uses and whether its image is upside down, as Markdown, JSON and JUnit XML, with an exit "
    "code a CI job gates on.",
    R"(Examples:
  vri-verify --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --size 80x60 \
             --steps 2,1,0.5,0.25 --report report.md --junit junit.xml \
             -- /usr/bin/python3 examples/scene_card/render_from_card.py {card} {output}
  vri-verify --field linear --tf experiments/tf/paper-a-linear.yaml --placement entry-exit-corner \
             --steps 1,0.5,0.25,0.125 -- ./my-renderer {card} {output} {stats}

The scene and method options are vri-render's: they describe the cards (docs/scene-card.md); --step is
replaced by each of --steps. With --placement given, a renderer that uses another placement fails; without,
the placement it uses is reported. The command and its placeholders are vri-outside's
(docs/outside-renderers.md). Exit codes: 0 every finding passed, 3 a finding failed (its message names
what is wrong), 1 the renderer could not be run or wrote no image, 64 a usage error.)"};

}  // namespace

int main(int argc, char** argv) { return vri::verifyMain(kHelp, argc, argv); }
