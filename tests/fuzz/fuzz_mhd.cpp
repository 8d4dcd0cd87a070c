// Fuzz target: MetaImage headers, read as the tools read a .mha or .mhd file (readVolume). The input is
// the whole file: a header naming data.raw beside it (ElementDataFile = data.raw), or one whose voxels
// follow it (ElementDataFile = LOCAL), raw or zlib-compressed. A vri::Error is a clean rejection;
// anything else (another exception, a sanitizer report, a crash) is a finding.
#include "fuzz_scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    vri::fuzz::readInputAsVolume("input.mha", data, size);
    return 0;
}
