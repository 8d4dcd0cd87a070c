// Fuzz target: transfer-function YAML (parseTransferFunction, what --tf files go through). A function
// that parses is also evaluated, in double and float, at every point, between neighbouring points and
// beyond both ends, where its segment lookup scales s by the points' span. A vri::Error is a clean
// rejection; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "libvri/core/transfer_function.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const vri::TransferFunction tf = vri::parseTransferFunction(text, "fuzz-tf.yaml");
        const auto& points = tf.points();
        std::vector<double> at{points.front().s - 1.0, points.back().s + 1.0, 0.0, 0.5, 1.0};
        for (std::size_t i = 0; i < points.size(); ++i) {
            at.push_back(points[i].s);
            if (i + 1 < points.size()) at.push_back(points[i].s + (points[i + 1].s - points[i].s) / 2);
        }
        for (const double s : at) {
            tf(s);
            tf(static_cast<float>(s));
        }
        tf.isInvisible(points.front().s, points.back().s);
    } catch (const vri::Error&) {
    }
    return 0;
}
