// Inviwo's .dat volume header: "Key: value" lines (keys case-insensitive) next to a raw file.
// Keys vri has no use for (ValueRange, ValueUnit, Wrapping, AxisNames, ...) are accepted and ignored.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>

#include "libvri/io/volume_formats.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

std::map<std::string, HeaderEntry> parseDat(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open");
    std::map<std::string, HeaderEntry> entries;
    std::string line;
    for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
        const std::string_view text = trim(line);
        if (text.empty() || text.front() == '#') continue;
        const std::size_t colon = text.find(':');
        if (colon == std::string_view::npos)
            throw Error(path.string() + ":" + std::to_string(lineNumber) + ": expected 'Key: value', got '" +
                        std::string(text) + "'");
        const std::string key(trim(text.substr(0, colon)));
        entries[toLower(key)] = {key, std::string(trim(text.substr(colon + 1))), lineNumber};
    }
    return entries;
}

}  // namespace

HeaderVoxels inviwoDatVoxels(const fs::path& path) {
    requireRegularFile(path);
    const std::map<std::string, HeaderEntry> entries = parseDat(path);
    const auto find = [&](const std::string& key) -> const HeaderEntry* {
        const auto it = entries.find(key);
        return it == entries.end() ? nullptr : &it->second;
    };
    const auto require = [&](const std::string& key, const std::string& spelling) -> const HeaderEntry& {
        if (const HeaderEntry* entry = find(key)) return *entry;
        throw Error(path.string() + ": required key '" + spelling + "' is missing");
    };
    const auto where = [&](const HeaderEntry& entry) {
        return path.string() + ":" + std::to_string(entry.line) + ": " + entry.key;
    };

    RawLayout layout;
    const HeaderEntry& format = require("format", "Format");
    layout.type = parseVoxelType(format.value, where(format));

    const HeaderEntry& resolution = require("resolution", "Resolution");
    const std::vector<double> dims = parseNumbers(resolution.value, 3, where(resolution));
    for (int axis = 0; axis < 3; ++axis) {
        // Compared before the cast: converting a double beyond int's range is undefined.
        if (!(dims[axis] >= 1 && dims[axis] <= std::numeric_limits<int>::max()) || dims[axis] != std::floor(dims[axis]))
            throw Error(where(resolution) + ": expected three positive integers up to " +
                        std::to_string(std::numeric_limits<int>::max()) + ", got '" + resolution.value + "'");
        layout.dims[axis] = static_cast<int>(dims[axis]);
    }

    if (const HeaderEntry* byteOrder = find("byteorder")) {
        const std::string order = toLower(byteOrder->value);
        if (order == "littleendian" || order == "little") layout.order = ByteOrder::Little;
        else if (order == "bigendian" || order == "big") layout.order = ByteOrder::Big;
        else throw Error(where(*byteOrder) + ": expected LittleEndian or BigEndian, got '" + byteOrder->value + "'");
    }
    if (const HeaderEntry* offset = find("byteoffset")) {
        layout.headerBytes = parseByteCount(offset->value, where(*offset));
    }

    // Inviwo spans the whole volume with its basis; the distance between samples is the basis
    // vector's length over the resolution along that axis.
    const HeaderEntry* basis[3] = {find("basisvector1"), find("basisvector2"), find("basisvector3")};
    if (basis[0] || basis[1] || basis[2]) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!basis[axis])
                throw Error(path.string() + ": BasisVector" + std::to_string(axis + 1) +
                            " is missing (the other basis vectors are given)");
            const std::vector<double> v = parseNumbers(basis[axis]->value, 3, where(*basis[axis]));
            for (int component = 0; component < 3; ++component)
                if ((component == axis) != (v[component] != 0.0) || v[axis] < 0.0)
                    throw Error(where(*basis[axis]) +
                                ": only axis-aligned volumes with positive basis vectors are supported, got '" +
                                basis[axis]->value + "'");
            layout.spacing[axis] = v[axis] / layout.dims[axis];
        }
    }

    // Checked as a raw file's layout is (a basis vector so short that its spacing underflows to 0).
    const fs::path rawPath = dataFileNamedBy(path, require("rawfile", "Rawfile").value);
    namingHeader(
        path, rawPath, [&] { requireValidLayout(rawPath, layout); }, "Rawfile");
    HeaderVoxels voxels{
        rawPath,        {layout.dims, storedTypeOf(layout.type), layout.order, layout.headerBytes, false},
        layout.spacing, std::nullopt,
        std::nullopt,   "Rawfile"};
    if (const HeaderEntry* range = find("datarange")) voxels.range = parseValueRange(range->value, where(*range));
    if (const HeaderEntry* offset = find("offset")) {
        const std::vector<double> o = parseNumbers(offset->value, 3, where(*offset));
        voxels.origin = glm::dvec3(o[0], o[1], o[2]);
    }
    return voxels;
}

void writeInviwoDat(const fs::path& path, const Volume& volume) {
    const fs::path rawPath = rawFileBeside(path);
    const auto n = [](double value) { return exactNumber(value); };
    const glm::dvec3 extent = volume.spacing * glm::dvec3(volume.dims);
    const glm::dvec3 o = volume.origin;
    std::string format(voxelTypeName(volume.type));
    std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return std::toupper(c); });
    std::string text = "Rawfile: " + rawPath.filename().string() + "\n"
                       "Resolution: " + std::to_string(volume.dims.x) + " " + std::to_string(volume.dims.y) + " " +
                       std::to_string(volume.dims.z) + "\n"
                       "Format: " + format + "\n"
                       "ByteOrder: LittleEndian\n";
    if (volume.range) text += "DataRange: " + n(volume.range->lo) + " " + n(volume.range->hi) + "\n";
    text += "BasisVector1: " + n(extent.x) + " 0 0\n"
            "BasisVector2: 0 " + n(extent.y) + " 0\n"
            "BasisVector3: 0 0 " + n(extent.z) + "\n"
            "Offset: " + n(o.x) + " " + n(o.y) + " " + n(o.z) + "\n";
    std::vector<std::byte> swapped;
    const OutputBytes files[] = {{rawPath, rawBytes(rawPath, volume, ByteOrder::Little, swapped)}, {path, text}};
    writeTogether(files);
}

}  // namespace vri::detail
