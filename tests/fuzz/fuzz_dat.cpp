// Fuzz target: Inviwo .dat headers, read as the tools read them (readVolume); the header may name
// data.raw beside it as its Rawfile. A vri::Error is a clean rejection; anything else is a finding.
#include "fuzz_scratch.h"
#include "vri/error.h"
#include "vri/volume_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path path = vri::fuzz::writeInput("input.dat", data, size);
    try {
        vri::readVolume(path);
    } catch (const vri::Error&) {
    }
    return 0;
}
