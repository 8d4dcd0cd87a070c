// NRRD (teem.sourceforge.net/nrrd/format.html): 3D scalar volumes, raw or gzip encoded, detached
// (.nhdr + data file) or attached (.nrrd, data after the header's blank line).
//
// Positions: NRRD's "space origin" is the centre of the first sample, whatever the centering; vri's
// Volume::origin is the corner of the box. An axis whose "centers" is cell (or unstated: teem's default,
// and what 3D Slicer and ITK mean) starts half a spacing before its first sample; a node axis starts on
// it. vri writes "centers: cell cell cell", its default convention, and the first sample's centre.
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
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// The header up to its blank line, field names lower-cased. Key/value pairs ("key:=value") are
// kept apart: they are free-form, and vri stores its normalisation range in one.
struct NrrdHeader {
    struct Field {
        std::string value;
        int line = 0;
    };
    std::map<std::string, Field> fields;
    std::map<std::string, Field> keyValues;
    std::optional<std::uintmax_t> dataOffset;  // attached data start right after the blank line
};

NrrdHeader parseNrrdHeader(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    if (!std::getline(in, line) || line.size() < 8 || line.compare(0, 7, "NRRD000") != 0 ||
        !std::isdigit(static_cast<unsigned char>(line[7])))
        throw Error(path.string() + ": not a NRRD file (the first line must be NRRD000X)");

    NrrdHeader header;
    for (int lineNumber = 2; std::getline(in, line); ++lineNumber) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) {
            header.dataOffset = static_cast<std::uintmax_t>(in.tellg());
            break;
        }
        if (line.front() == '#') continue;
        const std::size_t keyValue = line.find(":=");
        const std::size_t field = line.find(": ");
        if (keyValue != std::string::npos && keyValue < field) {
            header.keyValues[std::string(trim(line.substr(0, keyValue)))] = {
                std::string(trim(line.substr(keyValue + 2))), lineNumber};
        } else if (field != std::string::npos) {
            header.fields[toLower(trim(line.substr(0, field)))] = {std::string(trim(line.substr(field + 2))),
                                                                    lineNumber};
        } else {
            throw Error(path.string() + ":" + std::to_string(lineNumber) + ": expected 'field: value', got '" +
                        line + "'");
        }
    }
    return header;
}

// NRRD's type names (format.html, "type:"), with the integer types vri converts (stored_voxels.h).
StoredType parseNrrdType(const std::string& name, const std::string& where) {
    static const std::map<std::string, StoredType> kTypes = {
        {"signed char", StoredType::Int8},      {"int8", StoredType::Int8},
        {"int8_t", StoredType::Int8},           {"uchar", StoredType::UInt8},
        {"unsigned char", StoredType::UInt8},   {"uint8", StoredType::UInt8},
        {"uint8_t", StoredType::UInt8},         {"short", StoredType::Int16},
        {"short int", StoredType::Int16},       {"signed short", StoredType::Int16},
        {"signed short int", StoredType::Int16}, {"int16", StoredType::Int16},
        {"int16_t", StoredType::Int16},         {"ushort", StoredType::UInt16},
        {"unsigned short", StoredType::UInt16}, {"unsigned short int", StoredType::UInt16},
        {"uint16", StoredType::UInt16},         {"uint16_t", StoredType::UInt16},
        {"int", StoredType::Int32},             {"signed int", StoredType::Int32},
        {"int32", StoredType::Int32},           {"int32_t", StoredType::Int32},
        {"uint", StoredType::UInt32},           {"unsigned int", StoredType::UInt32},
        {"uint32", StoredType::UInt32},         {"uint32_t", StoredType::UInt32},
        {"float", StoredType::Float32},         {"double", StoredType::Float64},
    };
    const auto it = kTypes.find(toLower(trim(name)));
    if (it == kTypes.end())
        throw Error(where + ": '" + name + "' is not supported (8-, 16- or 32-bit integers, float or double)");
    return it->second;
}

// "(1,0,0) (0,2,0) (0,0,3)" → its numbers.
std::vector<double> parseVectors(const std::string& text, std::size_t count, const std::string& where) {
    std::string numbers = text;
    std::replace_if(numbers.begin(), numbers.end(), [](char c) { return c == '(' || c == ')' || c == ','; }, ' ');
    return parseNumbers(numbers, count, where);
}

// Each spacing positive and the box it spans, sizes x spacing, finite (1e308 x 8 voxels is not).
void requireSpanningSpacing(const RawLayout& layout, const std::string& where) {
    for (int axis = 0; axis < 3; ++axis)
        if (!(layout.spacing[axis] > 0.0) || !std::isfinite(layout.spacing[axis] * layout.dims[axis]))
            throw Error(where + ": spacing " + exactNumber(layout.spacing[axis]) + " along " + "xyz"[axis] +
                        " must be positive, and times " + std::to_string(layout.dims[axis]) +
                        " voxels within the range of a double");
}

}  // namespace

HeaderVoxels nrrdVoxels(const fs::path& path) {
    requireRegularFile(path);
    const NrrdHeader header = parseNrrdHeader(path);
    const auto where = [&](const std::string& name) {
        const auto it = header.fields.find(name);
        return path.string() + ":" + (it == header.fields.end() ? "" : std::to_string(it->second.line) + ":") +
               " " + name;
    };
    const auto optionalField = [&](const std::string& name) -> const std::string* {
        const auto it = header.fields.find(name);
        return it == header.fields.end() ? nullptr : &it->second.value;
    };
    const auto requiredField = [&](const std::string& name) -> const std::string& {
        if (const std::string* value = optionalField(name)) return *value;
        throw Error(path.string() + ": required field '" + name + "' is missing");
    };

    if (requiredField("dimension") != "3")
        throw Error(where("dimension") + ": must be 3 (a scalar volume), got " + requiredField("dimension"));

    RawLayout layout;
    HeaderVoxels result;
    result.entry = "data file";
    const StoredType storedType = parseNrrdType(requiredField("type"), where("type"));

    const std::vector<double> sizes = parseNumbers(requiredField("sizes"), 3, where("sizes"));
    for (int axis = 0; axis < 3; ++axis) {
        // Compared before the cast: converting a double beyond int's range is undefined.
        if (!(sizes[axis] >= 1 && sizes[axis] <= std::numeric_limits<int>::max()) || sizes[axis] != std::floor(sizes[axis]))
            throw Error(where("sizes") + ": sizes must be positive integers up to " +
                        std::to_string(std::numeric_limits<int>::max()) + ", got '" + requiredField("sizes") + "'");
        layout.dims[axis] = static_cast<int>(sizes[axis]);
    }

    const std::string encoding = toLower(requiredField("encoding"));
    if (encoding != "raw" && encoding != "gzip" && encoding != "gz")
        throw Error(where("encoding") + ": '" + encoding + "' is not supported (raw or gzip)");
    const bool gzip = encoding != "raw";

    if (const std::string* endian = optionalField("endian")) {
        const std::string order = toLower(*endian);
        if (order != "little" && order != "big")
            throw Error(where("endian") + ": expected little or big, got '" + *endian + "'");
        layout.order = order == "little" ? ByteOrder::Little : ByteOrder::Big;
    } else if (storedSize(storedType) > 1) {
        throw Error(path.string() + ": required field 'endian' is missing (" +
                    std::string(storedTypeName(storedType)) + " voxels)");
    }

    if (const std::string* directions = optionalField("space directions")) {
        const std::vector<double> m = parseVectors(*directions, 9, where("space directions"));
        for (int axis = 0; axis < 3; ++axis)
            for (int component = 0; component < 3; ++component)
                if ((component == axis) != (m[axis * 3 + component] != 0.0) || m[axis * 3 + axis] < 0.0)
                    throw Error(where("space directions") +
                                ": only axis-aligned grids with positive directions are supported, got '" +
                                *directions + "'");
        layout.spacing = {m[0], m[4], m[8]};
        requireSpanningSpacing(layout, where("space directions"));
    } else if (const std::string* spacings = optionalField("spacings")) {
        const std::vector<double> s = parseNumbers(*spacings, 3, where("spacings"));
        layout.spacing = {s[0], s[1], s[2]};
        requireSpanningSpacing(layout, where("spacings"));
    }

    if (const std::string* lineSkip = optionalField("line skip"); lineSkip && *lineSkip != "0")
        throw Error(where("line skip") + ": skipping lines is not supported");
    // -1: the data are the file's last bytes; otherwise a byte count.
    std::optional<std::uintmax_t> byteSkip = 0;
    if (const std::string* skip = optionalField("byte skip"))
        byteSkip = trim(*skip) == "-1" ? std::nullopt : std::optional(parseByteCount(*skip, where("byte skip")));
    // teem skips those bytes of the inflated data, a layout no writer vri knows of uses.
    if (gzip && byteSkip != std::uintmax_t{0})
        throw Error(where("byte skip") + ": skipping bytes of gzip-encoded data is not supported");

    // Per axis, how far the box starts before the first sample: half a spacing (cell) or none (node).
    glm::dvec3 firstSampleInset{0.5};
    if (const std::string* centers = optionalField("centers"); centers || optionalField("centerings")) {
        const std::string& text = centers ? *centers : *optionalField("centerings");
        const std::string at = where(centers ? "centers" : "centerings");
        std::vector<std::string> words;
        for (std::size_t i = 0; i < text.size();) {
            const std::size_t end = std::min(text.find_first_of(" \t", i), text.size());
            if (end > i) words.push_back(toLower(std::string_view(text).substr(i, end - i)));
            i = end + 1;
        }
        if (words.size() != 3)
            throw Error(at + ": expected 3 centerings (cell, node, ??? or none), got '" + text + "'");
        for (int axis = 0; axis < 3; ++axis) {
            if (words[axis] == "node") firstSampleInset[axis] = 0.0;
            else if (words[axis] != "cell" && words[axis] != "???" && words[axis] != "none")
                throw Error(at + ": expected cell, node, ??? or none, got '" + words[axis] + "'");
        }
    }

    const std::string* dataFile = optionalField("data file");
    if (!dataFile) dataFile = optionalField("datafile");
    fs::path dataPath = path;
    if (dataFile) {
        if (dataFile->find('%') != std::string::npos || dataFile->find(' ') != std::string::npos ||
            dataFile->starts_with("LIST"))
            throw Error(where(optionalField("data file") ? "data file" : "datafile") +
                        ": only a single data file is supported, got '" + *dataFile + "'");
        dataPath = dataFileNamedBy(path, *dataFile);
    } else if (!header.dataOffset) {
        throw Error(path.string() + ": no 'data file' field and no data after the header");
    }

    std::optional<std::uintmax_t> offset;  // nullopt: the data are the last bytes of the file
    if (byteSkip) {
        const std::uintmax_t headerEnd = dataFile ? 0 : *header.dataOffset;
        if (*byteSkip > std::numeric_limits<std::uintmax_t>::max() - headerEnd)
            throw Error(where("byte skip") + ": " + std::to_string(*byteSkip) + " bytes is too large");
        offset = headerEnd + *byteSkip;
    }
    result.dataPath = dataPath;
    result.data = {layout.dims, storedType, layout.order, offset, gzip};
    result.spacing = layout.spacing;
    if (const std::string* origin = optionalField("space origin")) {
        const std::vector<double> o = parseVectors(*origin, 3, where("space origin"));
        result.origin = glm::dvec3(o[0], o[1], o[2]) - firstSampleInset * layout.spacing;
    }
    if (const auto range = header.keyValues.find("vri_range"); range != header.keyValues.end()) {
        result.range = parseValueRange(range->second.value,
                                       path.string() + ":" + std::to_string(range->second.line) + ": vri_range");
    }
    return result;
}


void writeNrrd(const fs::path& path, const Volume& volume) {
    const bool attached = toLower(path.extension().string()) == ".nrrd";
    const fs::path rawPath = rawFileBeside(path);
    const std::string nrrdType = volume.type == VoxelType::Float32 ? "float" : std::string(voxelTypeName(volume.type));
    const glm::dvec3 s = volume.spacing;
    const glm::dvec3 c = volume.origin + 0.5 * s;  // the first sample's centre, cell-centred
    const auto n = [](double value) { return exactNumber(value); };
    std::string text = "NRRD0004\n"
                       "# written by vri\n"
                       "type: " + nrrdType + "\n"
                       "dimension: 3\n"
                       "sizes: " + std::to_string(volume.dims.x) + " " + std::to_string(volume.dims.y) + " " +
                       std::to_string(volume.dims.z) + "\n"
                       "centers: cell cell cell\n"
                       "space dimension: 3\n"
                       "space directions: (" + n(s.x) + ",0,0) (0," + n(s.y) + ",0) (0,0," + n(s.z) + ")\n"
                       "space origin: (" + n(c.x) + "," + n(c.y) + "," + n(c.z) + ")\n"
                       "endian: little\n"
                       "encoding: raw\n";
    if (!attached) text += "data file: " + rawPath.filename().string() + "\n";
    if (volume.range) text += "vri_range:=" + n(volume.range->lo) + " " + n(volume.range->hi) + "\n";
    std::vector<std::byte> swapped;
    const std::string_view voxels = rawBytes(attached ? path : rawPath, volume, ByteOrder::Little, swapped);
    if (attached) {
        writeTextFile(path, text + "\n" + std::string(voxels));
        return;
    }
    const OutputBytes files[] = {{rawPath, voxels}, {path, text}};
    writeTogether(files);
}

}  // namespace vri::detail
