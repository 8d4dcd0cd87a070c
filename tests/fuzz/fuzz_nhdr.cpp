// Fuzz target: NRRD headers, read as vri-convert and vri-render read a .nhdr or .nrrd file (readVolume).
// The input is the whole file: a detached header naming data.raw beside it, or a header with the data
// attached after its blank line. A vri::Error is a clean rejection; anything else (another exception,
// a sanitizer report, a crash) is a finding.
#include "fuzz_scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    vri::fuzz::readInputAsVolume("input.nhdr", data, size);
    return 0;
}
