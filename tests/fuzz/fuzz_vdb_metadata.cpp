// Fuzz target: the interpretation of an OpenVDB grid's metadata and transform (vdbVolumeLayout), fed
// plain values instead of .vdb files: OpenVDB's own reader is not instrumented, so fuzzing whole files
// would mostly exercise code that is not vri's. The input is text, one "key: values" line per fact
// (see corpus/vdb_metadata); unknown keys and malformed values leave that fact at its default.
//   value_type: float | double | int32 | int64     transform: linear | nonlinear     matrix: 9 numbers, row by row
//   vri_voxel_type: NAME     vri_dims: X Y Z     vri_range: LO HI     vri_format_version: N
//   active: X0 Y0 Z0 X1 Y1 Z1
// A vri::Error is a clean rejection. A layout that is accepted must describe a box whose corners fit
// OpenVDB's 32-bit coordinates (the reader builds a CoordBBox from it); anything else is a finding.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "libvri/io/vdb_grid_layout.h"
#include "libvri/util/error.h"

namespace {

template <class T>
std::vector<T> numbers(std::string_view text) {
    std::vector<T> values;
    const char* p = text.data();
    const char* end = text.data() + text.size();
    while (p < end) {
        while (p < end && *p == ' ')
            ++p;
        T value{};
        const auto [next, ec] = std::from_chars(p, end, value);
        if (ec != std::errc{}) break;
        values.push_back(value);
        p = next;
    }
    return values;
}

vri::detail::VdbGridFacts decode(const std::string& text) {
    vri::detail::VdbGridFacts facts;
    facts.description = "grid 'density' (fuzzed)";
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const std::size_t colon = line.find(": ");
        if (colon == std::string::npos) continue;
        const std::string key = line.substr(0, colon);
        const std::string_view value = std::string_view(line).substr(colon + 2);
        if (key == "value_type") {
            if (value == "double")
                facts.valueType = vri::detail::VdbValueType::Double;
            else if (value == "int32")
                facts.valueType = vri::detail::VdbValueType::Int32;
            else if (value == "int64")
                facts.valueType = vri::detail::VdbValueType::Int64;
            else
                facts.valueType = vri::detail::VdbValueType::Float;
        } else if (key == "transform") {
            facts.linearTransform = value != "nonlinear";
        } else if (key == "matrix") {
            if (const auto m = numbers<double>(value); m.size() == 9)
                for (int row = 0; row < 3; ++row)
                    for (int column = 0; column < 3; ++column)
                        facts.linear[column][row] = m[row * 3 + column];
        } else if (key == "vri_voxel_type") {
            facts.voxelTypeMeta = std::string(value);
        } else if (key == "vri_dims") {
            if (const auto d = numbers<int>(value); d.size() == 3) facts.dimsMeta = glm::ivec3(d[0], d[1], d[2]);
        } else if (key == "vri_range") {
            if (const auto r = numbers<double>(value); r.size() == 2) facts.rangeMeta = glm::dvec2(r[0], r[1]);
        } else if (key == "vri_format_version") {
            if (const auto v = numbers<int>(value); v.size() == 1) facts.formatVersionMeta = v[0];
        } else if (key == "active") {
            if (const auto b = numbers<int>(value); b.size() == 6) {
                facts.activeMin = glm::ivec3(b[0], b[1], b[2]);
                facts.activeMax = glm::ivec3(b[3], b[4], b[5]);
            }
        }
    }
    return facts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const vri::detail::VdbGridFacts facts = decode(std::string(reinterpret_cast<const char*>(data), size));
    try {
        const vri::detail::VdbVolumeLayout layout = vri::detail::vdbVolumeLayout("fuzz.vdb", facts);
        for (int axis = 0; axis < 3; ++axis) {
            const std::int64_t last = std::int64_t{layout.boxMin[axis]} + layout.dims[axis] - 1;
            if (layout.dims[axis] < 1 || last > std::numeric_limits<int>::max()) {
                std::fprintf(stderr, "fuzz: accepted a box that does not fit 32-bit coordinates (axis %d)\n", axis);
                std::abort();
            }
        }
    } catch (const vri::Error&) {
    }
    return 0;
}
