// Fuzz target: a last manifest as vri-run reads it back to price the steps it plans (step_costs.h: the
// progress line's ETA, --estimate, the Slurm jobs' --time). The input is written as the experiment's
// manifest.json and read for a plan of three steps. A vri::Error is a clean rejection; anything else is a
// finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_scratch.h"
#include "libvri/experiment/step_costs.h"
#include "libvri/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto manifest = vri::fuzz::writeInput("manifest.json", data, size);
    vri::Plan plan{vri::fuzz::scratchDir(), vri::fuzz::scratchDir(), {}, {}};
    plan.steps = {vri::Step{"a", "render", "vri-render", {"--size", "8x6", "-o", "a.exr"}, {}, {}, {}},
                  vri::Step{"b", "diff", "vri-diff", {"a.exr", "b.exr"}, {}, {}, {}},
                  vri::Step{"c", "table", "vri-tabulate", {"-o", "c.md"}, {}, {}, {}}};
    try {
        const vri::CostEstimate estimate = vri::estimateCost(plan, manifest);
        vri::secondsText(estimate.seconds);
    } catch (const vri::Error&) {
    }
    return 0;
}
