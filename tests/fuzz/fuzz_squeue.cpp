// Fuzz target: what the Slurm clients print and vri-run reads back (slurm_commands.h): squeue's job lines
// (parseSqueue), sbatch --parsable's job id (parseSbatchJobId) and each job state a line gives
// (isFinalJobState). A vri::Error is a clean rejection; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "libvri/experiment/slurm_commands.h"
#include "libvri/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        for (const auto& [id, job] : vri::parseSqueue(text)) vri::isFinalJobState(job.state);
    } catch (const vri::Error&) {
    }
    try {
        vri::parseSbatchJobId(text);
    } catch (const vri::Error&) {
    }
    return 0;
}
