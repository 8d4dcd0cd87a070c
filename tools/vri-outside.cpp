// vri-outside: another renderer's image of a vri scene, through the scene card, as a run of vri's own.
#include "common/render_main.h"

namespace {

constexpr vri::RenderCommandHelp kHelp{
    "Run an outside renderer on a vri scene: writes the scene card (and the volume's voxels) that vri-render's "
    "scene and method options describe, runs the renderer's command given after --, and writes its image as "
    "float RGBA OpenEXR, an optional PNG preview and a stats file in vri's form, so that vri-diff, vri-tabulate "
    "and the charts take it like one of vri's own runs.",
    R"(Examples:
  vri-outside --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --size 160x120 \
              --step 0.5 -o numpy.exr --stats numpy.json \
              -- /usr/bin/python3 examples/scene_card/render_from_card.py {card} {output}
  vri-outside --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --step 1 \
              --renderer-image f32 -o three.exr -- node tools/peers/web/three.mjs {card} {output} {stats}

The command runs without a shell, from the current folder, with these placeholders filled in: {card} (the
scene card, docs/scene-card.md), {voxels} (its raw voxels), {output} (where the renderer writes its image:
image.exr, image.png or image.f32 by --renderer-image), {stats} (where it may write its statistics,
docs/outside-renderers.md), {step} (the step in voxels), {seed} (a jittered card's seed), {width}, {height};
{{ and }} are braces. Its image must be RGBA, premultiplied, linear, over a (0, 0, 0, 0) background, row 0 at
the top, as the card says. Timing: the renderer's own frame times when its stats give them ("timed": "frame"),
else the whole command's wall time ("timed": "process").)"};

}  // namespace

int main(int argc, char** argv) { return vri::outsideMain(kHelp, argc, argv); }
