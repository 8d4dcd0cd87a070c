// Fuzz target: Inviwo .dat headers, read as the tools read them (readVolume); the header may name
// data.raw beside it as its Rawfile. A vri::Error is a clean rejection; anything else is a finding.
#include "fuzz_scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    vri::fuzz::readInputAsVolume("input.dat", data, size);
    return 0;
}
