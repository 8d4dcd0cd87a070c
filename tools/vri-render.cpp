// vri-render: renders one image of a volume or analytic field with the CPU raycaster or the Vulkan backend.
#include "common/render_main.h"

namespace {

constexpr vri::RenderCommandHelp kHelp{
    "Render a volume (or an analytic field) with the CPU raycaster or on a Vulkan device: float RGBA "
    "OpenEXR, an optional 8-bit PNG preview and a JSON stats file.",
    R"(Examples:
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml \
             --size 800x600 --step 0.5 -o bonsai.exr --png bonsai.png --stats bonsai.json
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --method coupled \
             --tolerance 0.01 --log-ray 400,300 --log ray.csv -o coupled.exr --stats coupled.json
  vri-render --field linear --field-dims 5,5,5 --convention node --tf experiments/tf/paper-a-linear.yaml \
             --placement entry-exit-corner --rate 1 --eye -9,0,0 --target 0,0,0 --fov 30 -o corner.exr

  vri-render --backend vulkan --device llvmpipe --volume bonsai_256x256x256_uint8.raw \
             --tf experiments/tf/paper-b-bonsai.yaml --method coupled -o coupled-vk.exr
  vri-render --backend vulkan --interpolation sampler --volume bonsai_256x256x256_uint8.raw \
             --tf experiments/tf/paper-b-bonsai.yaml --step 0.1 -o riemann-sampler.exr
  vri-render --list-devices
  vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/paper-b-bonsai.yaml --method exact \
             --tolerance 1e-7 -o exact.exr --stats exact.json

exact: vri-reference's method (pieces on which the field is a cubic, Gauss-Kronrod quadrature), in double
on the CPU; --tolerance is the error allowed per transfer-function piece (default 1e-7 for exact) and the
stats give the per-pixel error bound ("error_bound": max and mean per channel). The bound is for the double
value; the EXR holds float32, which adds up to half an ulp of each value: "stored_max" and --error-image
bound the float32 value (the double's bound plus its rounding).
Steps are in voxels: --step h is --rate 1/h. Colours are in the TF's units, alpha = 1 - transparency
(Simpson methods: alpha = the integral of extinction times transparency, paper B's fourth channel).
A quadrature can return colour and alpha above 1: the Simpson methods overshoot on steep rises (decoupled
without --h-max most), a Riemann sum where tau * h is large; the stats count such pixels and give the
largest value ("out_of_range_pixels"); --clamp clamps them to [0, 1] after counting.

Limits, checked before any work: a volume or image may take at most 16 GiB (set VRI_MAX_BYTES to a byte
count to change it); a ray at most 1e9 samples (--step, --rate) or, for the Simpson methods, 1e9 steps of
h_min (2^22 in float precision, where a shorter step would no longer advance the ray).)"};

}  // namespace

int main(int argc, char** argv) { return vri::renderMain(vri::RenderTool::Render, kHelp, argc, argv); }
