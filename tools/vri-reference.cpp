// vri-reference: the reference image of a scene, solved accurately with a bound on its error, or as
// paper B computed its reference (a Riemann sum with a 0.01-voxel step).
#include "common/render_main.h"

namespace {

constexpr vri::RenderCommandHelp kHelp{
    "Reference image of a volume (or an analytic field): the volume rendering integral along each "
    "pixel's ray solved to near double precision with a bound on its error (--method exact), or "
    "paper B's reference, a Riemann sum with a small step (--method riemann). Float RGBA OpenEXR, "
    "an optional PNG preview, error-bound image and JSON stats.",
    R"(Examples:
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                -o bonsai-exact.exr --error-image bonsai-bound.exr --stats bonsai-exact.json
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                --method riemann --step 0.01 -o bonsai-riemann.exr
  vri-diff bonsai-riemann.exr bonsai-exact.exr --threshold 0.001

exact: the ray is split where the trilinear field changes form (voxel-index planes) and where it crosses a
transfer-function point; on each piece the scalar, extinction and colour are cubics, the optical depth an
exact quartic, and the outer integral adaptive Gauss-Kronrod. The stats give the error bound per channel,
for the double value; the EXR holds float32, which adds up to half an ulp of each value (often more than
the bound): the stats' "stored_max" and --error-image bound the float32 value (the double's bound plus its
rounding, rounded up).
riemann: vri-render's Riemann sum, entry placement, double precision, --step in voxels.)"};

}  // namespace

int main(int argc, char** argv) { return vri::renderMain(vri::RenderTool::Reference, kHelp, argc, argv); }
