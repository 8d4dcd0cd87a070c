// Fuzz target: transfer-function YAML (parseTransferFunction, what --tf files go through). A function
// that parses is also evaluated across and beyond [0, 1], where its segment lookup divides by the
// points' spacing. A vri::Error is a clean rejection; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "vri/error.h"
#include "vri/transfer_function.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const vri::TransferFunction tf = vri::parseTransferFunction(text, "fuzz-tf.yaml");
        for (const double s : {-1.0, 0.0, 0.25, 0.5, 0.75, 1.0, 2.0}) {
            tf(s);
            tf(static_cast<float>(s));
        }
        tf.isInvisible(0.0, 1.0);
    } catch (const vri::Error&) {
    }
    return 0;
}
