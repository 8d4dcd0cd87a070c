// Fuzz target: experiment files (parseExperiment, what vri-run reads), full and --quick. Relative paths
// resolve against the repository's experiments/ folder, so that tf/*.yaml and datasets.yaml exist.
// A vri::Error is a clean rejection; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "libvri/experiment/experiment_spec.h"
#include "libvri/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    for (const bool quick : {false, true}) {
        try {
            vri::parseExperiment(text, "fuzz-experiment.yaml", VRI_FUZZ_EXPERIMENTS_DIR, quick);
        } catch (const vri::Error&) {
        }
    }
    return 0;
}
