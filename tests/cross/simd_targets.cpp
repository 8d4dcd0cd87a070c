// vri-simd-targets (VRI_CORE_ONLY builds, scripts/check-neon): the SIMD targets this CPU and build have, best
// first, one a line, as --simd and VRI_SIMD_TARGET name them; under qemu-user, the ones the emulated CPU runs.
#include <iostream>

#include "libvri/core/simd_target.h"

int main() {
    for (const std::string& target : vri::availableSimdTargets()) std::cout << target << '\n';
}
