// MetaImage (ITK's MetaIO): "Key = Value" header lines, the voxels in a file named by ElementDataFile
// (.mhd) or right after the header when that is LOCAL (.mha), raw or zlib-compressed.
//
// Positions: Offset (or Origin, Position) is the centre of voxel (0,0,0), as in ITK, whose voxels are
// cells around their centres; vri's Volume::origin, the box corner, is half a spacing before it.
#include <fstream>
#include <map>
#include <optional>

#include "libvri/io/volume_formats.h"
#include "libvri/util/error.h"

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

struct MetaHeader {
    std::map<std::string, HeaderEntry> entries;  // by lower-cased key
    std::uintmax_t dataOffset = 0;             // the byte after the ElementDataFile line
};

// Lines up to and including ElementDataFile, which MetaIO requires to be the last.
MetaHeader parseMetaHeader(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open");
    MetaHeader header;
    std::string line;
    for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
        const std::string_view text = trim(line);
        if (text.empty()) continue;
        const std::size_t equals = text.find('=');
        if (equals == std::string_view::npos)
            throw Error(path.string() + ":" + std::to_string(lineNumber) + ": expected 'Key = Value', got '" +
                        std::string(text) + "'");
        const std::string key(trim(text.substr(0, equals)));
        header.entries[toLower(key)] = {key, std::string(trim(text.substr(equals + 1))), lineNumber};
        if (toLower(key) == "elementdatafile") {
            header.dataOffset = static_cast<std::uintmax_t>(in.tellg());
            return header;
        }
        if (lineNumber > 1000) break;
    }
    throw Error(path.string() + ": no ElementDataFile line (a MetaImage header ends with it)");
}

StoredType parseElementType(const std::string& name, const std::string& where) {
    static const std::map<std::string, StoredType> kTypes = {
        {"MET_CHAR", StoredType::Int8},   {"MET_UCHAR", StoredType::UInt8},  {"MET_SHORT", StoredType::Int16},
        {"MET_USHORT", StoredType::UInt16}, {"MET_INT", StoredType::Int32},  {"MET_UINT", StoredType::UInt32},
        {"MET_FLOAT", StoredType::Float32}, {"MET_DOUBLE", StoredType::Float64},
    };
    const auto it = kTypes.find(name);
    if (it == kTypes.end())
        throw Error(where + ": '" + name + "' is not supported (MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, MET_INT, "
                            "MET_UINT, MET_FLOAT or MET_DOUBLE)");
    return it->second;
}

bool parseBool(const HeaderEntry& entry, const std::string& where) {
    const std::string v = toLower(entry.value);
    if (v == "true" || v == "1") return true;
    if (v == "false" || v == "0") return false;
    throw Error(where + ": expected True or False, got '" + entry.value + "'");
}

}  // namespace

HeaderVoxels metaImageVoxels(const fs::path& path) {
    requireRegularFile(path);
    const MetaHeader header = parseMetaHeader(path);
    const auto find = [&](const std::string& key) -> const HeaderEntry* {
        const auto it = header.entries.find(key);
        return it == header.entries.end() ? nullptr : &it->second;
    };
    const auto where = [&](const HeaderEntry& entry) {
        return path.string() + ":" + std::to_string(entry.line) + ": " + entry.key;
    };
    const auto require = [&](const std::string& key, const std::string& spelling) -> const HeaderEntry& {
        if (const HeaderEntry* entry = find(key)) return *entry;
        throw Error(path.string() + ": required key '" + spelling + "' is missing");
    };

    if (const HeaderEntry* type = find("objecttype"); type && toLower(type->value) != "image")
        throw Error(where(*type) + ": expected Image, got '" + type->value + "'");
    const HeaderEntry& ndims = require("ndims", "NDims");
    if (trim(ndims.value) != "3") throw Error(where(ndims) + ": must be 3 (a scalar volume), got " + ndims.value);
    if (const HeaderEntry* channels = find("elementnumberofchannels"); channels && trim(channels->value) != "1")
        throw Error(where(*channels) + ": must be 1 (a scalar volume), got " + channels->value);

    VoxelData data;
    const HeaderEntry& dimSize = require("dimsize", "DimSize");
    const std::vector<double> dims = parseNumbers(dimSize.value, 3, where(dimSize));
    for (int axis = 0; axis < 3; ++axis) {
        // Compared before the cast: converting a double beyond int's range is undefined.
        if (!(dims[axis] >= 1 && dims[axis] <= 2147483647.0) || dims[axis] != static_cast<double>(static_cast<long long>(dims[axis])))
            throw Error(where(dimSize) + ": expected three positive integers up to 2147483647, got '" +
                        dimSize.value + "'");
        data.dims[axis] = static_cast<int>(dims[axis]);
    }
    const HeaderEntry& elementType = require("elementtype", "ElementType");
    data.type = parseElementType(std::string(trim(elementType.value)), where(elementType));

    for (const char* key : {"binarydatabyteordermsb", "elementbyteordermsb"})
        if (const HeaderEntry* msb = find(key)) data.order = parseBool(*msb, where(*msb)) ? ByteOrder::Big : ByteOrder::Little;
    if (const HeaderEntry* binary = find("binarydata"); binary && !parseBool(*binary, where(*binary)))
        throw Error(where(*binary) + ": ASCII voxel data are not supported (BinaryData = True)");
    if (const HeaderEntry* compressed = find("compresseddata")) data.gzip = parseBool(*compressed, where(*compressed));

    // Direction cosines other than the identity rotate or flip the grid.
    for (const char* key : {"transformmatrix", "rotation", "orientation"})
        if (const HeaderEntry* matrix = find(key)) {
            const std::vector<double> m = parseNumbers(matrix->value, 9, where(*matrix));
            for (int i = 0; i < 9; ++i)
                if (m[i] != (i % 4 == 0 ? 1.0 : 0.0))
                    throw Error(where(*matrix) + ": only the identity is supported (axis-aligned grids), got '" +
                                matrix->value + "'");
        }

    glm::dvec3 spacing{1.0};
    if (const HeaderEntry* s = find("elementspacing")) {
        const std::vector<double> v = parseNumbers(s->value, 3, where(*s));
        for (int axis = 0; axis < 3; ++axis) {
            if (!(v[axis] > 0.0))
                throw Error(where(*s) + ": expected positive spacings, got '" + s->value + "'");
            spacing[axis] = v[axis];
        }
    }

    const HeaderEntry& dataFile = require("elementdatafile", "ElementDataFile");
    fs::path dataPath = path;
    if (toLower(dataFile.value) == "local") {
        data.offset = header.dataOffset;
    } else {
        if (toLower(dataFile.value).starts_with("list") || dataFile.value.find('%') != std::string::npos ||
            dataFile.value.find(' ') != std::string::npos)
            throw Error(where(dataFile) + ": only LOCAL or a single data file is supported, got '" + dataFile.value +
                        "'");
        dataPath = dataFileNamedBy(path, dataFile.value);
        data.offset = 0;
        if (const HeaderEntry* headerSize = find("headersize")) {
            if (trim(headerSize->value) == "-1") {
                if (data.gzip) throw Error(where(*headerSize) + ": -1 (the last bytes) with compressed data is not supported");
                data.offset.reset();
            } else {
                data.offset = parseByteCount(headerSize->value, where(*headerSize));
            }
        }
    }

    HeaderVoxels voxels{dataPath, data, spacing, std::nullopt, std::nullopt, "ElementDataFile"};
    for (const char* key : {"offset", "origin", "position"})
        if (const HeaderEntry* offset = find(key)) {
            const std::vector<double> o = parseNumbers(offset->value, 3, where(*offset));
            voxels.origin = glm::dvec3(o[0], o[1], o[2]) - 0.5 * spacing;
        }
    return voxels;
}

}  // namespace vri::detail
