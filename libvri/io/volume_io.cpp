// Format dispatch, headerless raw files and the text helpers shared by the header formats.
#include "libvri/io/volume_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <utility>

#include "libvri/io/gzip_inflate.h"
#include "libvri/io/volume_formats.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/printable.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

std::string dimsText(glm::ivec3 dims) {
    return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
}

void reverseEachVoxel(std::vector<std::byte>& bytes, std::size_t voxelBytes) {
    if (voxelBytes < 2) return;
    for (auto it = bytes.begin(); it != bytes.end(); it += static_cast<std::ptrdiff_t>(voxelBytes))
        std::reverse(it, it + static_cast<std::ptrdiff_t>(voxelBytes));
}

std::optional<glm::ivec3> parseDimsToken(std::string_view token) {
    glm::ivec3 dims;
    for (int axis = 0; axis < 3; ++axis) {
        const std::size_t end = axis < 2 ? token.find('x') : token.size();
        if (end == std::string_view::npos || end == 0) return std::nullopt;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + end, dims[axis]);
        if (ec != std::errc{} || ptr != token.data() + end || dims[axis] < 1) return std::nullopt;
        token.remove_prefix(std::min(end + 1, token.size()));
    }
    return dims;
}

}  // namespace

namespace detail {

void requireValidLayout(const fs::path& path, const RawLayout& layout) {
    const glm::ivec3 d = layout.dims;
    if (d.x < 1 || d.y < 1 || d.z < 1)
        throw Error(path.string() + ": dimensions must be at least 1x1x1, got " + dimsText(d));
    const glm::dvec3 s = layout.spacing;
    for (int axis = 0; axis < 3; ++axis)
        if (!(s[axis] > 0.0) || !std::isfinite(s[axis]))
            throw Error(path.string() + ": spacing must be positive and finite, got " + exactNumber(s.x) + " " +
                        exactNumber(s.y) + " " + exactNumber(s.z));
}

std::optional<HeaderVoxels> headerVoxels(const fs::path& path) {
    const std::string extension = toLower(path.extension().string());
    if (extension == ".nhdr" || extension == ".nrrd") return nrrdVoxels(path);
    if (extension == ".mhd" || extension == ".mha") return metaImageVoxels(path);
    if (extension == ".dat") return inviwoDatVoxels(path);
    return std::nullopt;
}

Volume readHeaderVoxels(const fs::path& header, const HeaderVoxels& voxels) {
    Volume volume = namingHeader(
        header, voxels.dataPath, [&] { return readVoxelData(voxels.dataPath, voxels.data); }, voxels.entry);
    volume.spacing = voxels.spacing;
    if (voxels.origin) volume.origin = *voxels.origin;
    if (voxels.range) volume.range = voxels.range;
    return volume;
}

void requireRegularFile(const fs::path& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(path.string() + ": no such file");
    if (!fs::is_regular_file(status)) throw Error(path.string() + ": not a regular file");
}

std::string_view rawBytes(const fs::path& path, const Volume& volume, ByteOrder order,
                          std::vector<std::byte>& swapped) {
    if (volume.bytes.size() != volume.byteCount())
        throw Error(path.string() + ": volume holds " + std::to_string(volume.bytes.size()) + " bytes, expected " +
                    std::to_string(volume.byteCount()) + " for " + dimsText(volume.dims));
    const std::vector<std::byte>* bytes = &volume.bytes;
    if (order != nativeByteOrder() && voxelSize(volume.type) > 1) {
        swapped = volume.bytes;
        reverseEachVoxel(swapped, voxelSize(volume.type));
        bytes = &swapped;
    }
    return {reinterpret_cast<const char*>(bytes->data()), bytes->size()};
}

StoredVoxels storedVoxels(const fs::path& path, const VoxelData& data) {
    requireRegularFile(path);
    StoredVoxels s{0, 0, fs::file_size(path), dimsText(data.dims) + " " + std::string(storedTypeName(data.type))};
    const std::optional<std::uint64_t> bytes = checkedProduct(
        {std::uint64_t(data.dims.x), std::uint64_t(data.dims.y), std::uint64_t(data.dims.z), storedSize(data.type)});
    if (!bytes) throw Error(path.string() + ": " + s.layoutText + " needs more than 2^64 bytes");
    s.bytes = *bytes;
    // The data as the last bytes: whatever precedes them is header (none when the file is too short, and
    // the size check names both sizes).
    s.offset = data.offset.value_or(s.fileBytes - std::min<std::uintmax_t>(s.fileBytes, s.bytes));
    return s;
}

namespace {

// Uncompressed voxels: the file holds exactly the header and them.
void requireExactSize(const fs::path& path, const StoredVoxels& s) {
    if (s.bytes > std::numeric_limits<std::uintmax_t>::max() - s.offset)
        throw Error(path.string() + ": header of " + std::to_string(s.offset) + " bytes is too large");
    if (s.fileBytes != s.bytes + s.offset)
        throw Error(path.string() + ": file is " + std::to_string(s.fileBytes) + " bytes, expected " +
                    std::to_string(s.bytes + s.offset) + " for " + s.layoutText +
                    (s.offset > 0 ? " after a " + std::to_string(s.offset) + "-byte header" : ""));
}

}  // namespace

Volume readVoxelData(const fs::path& path, const VoxelData& data) {
    const StoredVoxels stored = storedVoxels(path, data);
    const std::uintmax_t fileBytes = stored.fileBytes, offset = stored.offset;
    const std::string& layoutText = stored.layoutText;
    if (data.gzip) {
        if (offset > fileBytes)
            throw Error(path.string() + ": file is " + std::to_string(fileBytes) + " bytes, its compressed data start at byte " +
                        std::to_string(offset));
        checkedUnpackedBytes(path.string() + ": " + layoutText, {stored.bytes}, fileBytes - offset, "compressed data",
                             kPlausibleCompressedExpansion);
        std::vector<std::byte> bytes =
            inflateFile(path, offset, stored.bytes, path.string() + ": gzip data of " + layoutText);
        const VoxelType volumeType = volumeTypeFor(data.type);
        if (storedTypeOf(volumeType) == data.type) {  // kept as stored: the inflated bytes become the volume
            Volume volume;
            volume.dims = data.dims;
            volume.type = volumeType;
            volume.bytes = std::move(bytes);
            if (data.order != nativeByteOrder()) reverseEachVoxel(volume.bytes, voxelSize(volumeType));
            return volume;
        }
        // The output of a stored type that vri converts is a second buffer beside the volume.
        return decodeVoxels(path.string(), data.dims, data.type, data.order,
                            {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
    }
    requireExactSize(path, stored);

    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(offset));
    const VoxelType volumeType = volumeTypeFor(data.type);
    if (storedTypeOf(volumeType) == data.type) {  // kept as stored: read straight into the volume
        Volume volume(data.dims, volumeType);
        in.read(reinterpret_cast<char*>(volume.bytes.data()), static_cast<std::streamsize>(volume.bytes.size()));
        if (!in) throw Error(path.string() + ": read failed");
        if (data.order != nativeByteOrder()) reverseEachVoxel(volume.bytes, voxelSize(volumeType));
        return volume;
    }
    const std::string what = path.string() + ": " + layoutText;
    const std::size_t size = checkedBytes(what, {stored.bytes});
    std::string bytes;
    allocateOrExplain(what, size, [&] { bytes.resize(size); });
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!in) throw Error(path.string() + ": read failed");
    return decodeVoxels(path.string(), data.dims, data.type, data.order, bytes);
}

fs::path dataFileNamedBy(const fs::path& headerPath, std::string_view value) {
    const fs::path named(value);
    return named.is_absolute() ? named : headerPath.parent_path() / named;
}

fs::path rawFileBeside(const fs::path& headerPath) {
    fs::path raw = headerPath;
    return raw.replace_extension(".raw");
}

std::string_view trim(std::string_view text) {
    const auto isSpace = [](unsigned char c) { return std::isspace(c) != 0; };
    while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
    return text;
}

std::string toLower(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    return lower;
}

std::vector<double> parseNumbers(std::string_view text, std::size_t count, const std::string& where) {
    std::vector<double> numbers;
    text = trim(text);
    while (!text.empty()) {
        const std::size_t end = std::min(text.find_first_of(" \t"), text.size());
        double value = 0.0;
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + end, value);
        if (ec != std::errc{} || ptr != text.data() + end || !std::isfinite(value))
            throw Error(where + ": '" + std::string(text.substr(0, end)) + "' is not a finite number");
        numbers.push_back(value);
        text = trim(text.substr(end));
    }
    if (numbers.size() != count)
        throw Error(where + ": expected " + std::to_string(count) + " numbers, got " + std::to_string(numbers.size()));
    return numbers;
}

std::uintmax_t parseByteCount(std::string_view text, const std::string& where) {
    text = trim(text);
    std::uintmax_t bytes = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), bytes);
    if (ec == std::errc::result_out_of_range) throw Error(where + ": " + std::string(text) + " bytes is too large");
    if (text.empty() || ec != std::errc{} || ptr != text.data() + text.size())
        throw Error(where + ": expected a byte count (a whole number, 0 or more), got '" + std::string(text) + "'");
    return bytes;
}

ValueRange parseValueRange(std::string_view text, const std::string& where) {
    const std::vector<double> r = parseNumbers(text, 2, where);
    if (!(r[0] < r[1]))
        throw Error(where + ": expected lo < hi, got '" + std::string(trim(text)) +
                    "' (an empty or inverted range maps every value to one end)");
    return {r[0], r[1]};
}

std::string nonFiniteVoxel(glm::ivec3 at, glm::ivec3 dims, double value, const std::string& source) {
    const std::uint64_t index =
        (static_cast<std::uint64_t>(at.z) * static_cast<std::uint64_t>(dims.y) + static_cast<std::uint64_t>(at.y)) *
            static_cast<std::uint64_t>(dims.x) +
        static_cast<std::uint64_t>(at.x);
    return source + ": voxel " + std::to_string(index) + " (x " + std::to_string(at.x) + ", y " + std::to_string(at.y) +
           ", z " + std::to_string(at.z) + ") is " + exactNumber(value) + ": float volumes must hold finite values";
}

}  // namespace detail

// What every reader's volume must hold, whatever its format says: finite float voxels (a NaN compares
// false with everything and would reach the image through the transfer function), a normalisation
// range with lo < hi (metadata of a .vdb included), and a box that a double can span.
namespace {

// The first non-finite float voxel of `volume`, whose first voxel sits at `start` in a volume of `dims` (0 and
// its own dims, or a brick's stored box), named by its place in that volume.
void requireFiniteVoxels(const Volume& volume, glm::ivec3 start, glm::ivec3 dims, const std::string& source) {
    if (volume.type != VoxelType::Float32) return;
    const float* v = volume.data<float>();
    const std::size_t n = volume.voxelCount();
    const auto isBad = [](float x) { return !std::isfinite(x); };
    const std::size_t bad = static_cast<std::size_t>(std::find_if(v, v + n, isBad) - v);
    if (bad == n) return;
    const auto bx = static_cast<std::size_t>(volume.dims.x), by = static_cast<std::size_t>(volume.dims.y);
    const glm::ivec3 at = start + glm::ivec3(static_cast<int>(bad % bx), static_cast<int>(bad / bx % by),
                                             static_cast<int>(bad / bx / by));
    throw Error(detail::nonFiniteVoxel(at, dims, v[bad], source));
}

}  // namespace

namespace detail {

ValueRange boxValueRange(const Volume& box, glm::ivec3 start, glm::ivec3 dims, const std::string& source) {
    requireFiniteVoxels(box, start, dims, source);
    return box.dataRange();
}

}  // namespace detail

void requireUsableGeometry(glm::ivec3 dims, glm::dvec3 spacing, glm::dvec3 origin,
                           const std::optional<ValueRange>& range, const std::string& source) {
    // Values map to (v - lo) / (hi - lo): a width past the largest double maps every value to 0.
    if (range && !(range->lo < range->hi && std::isfinite(range->hi - range->lo)))
        throw Error(source + ": value range " + exactNumber(range->lo) + " " + exactNumber(range->hi) +
                    ": expected finite lo < hi with a finite hi - lo");
    for (int axis = 0; axis < 3; ++axis) {
        const double end = origin[axis] + spacing[axis] * dims[axis];
        if (!std::isfinite(end))
            throw Error(source + ": the box (origin " + exactNumber(origin[axis]) + " + " + std::to_string(dims[axis]) +
                        " voxels x spacing " + exactNumber(spacing[axis]) + " along " + "xyz"[axis] +
                        ") is beyond the range of a double");
    }
}

void requireUsableValues(const Volume& volume, const std::string& source) {
    requireFiniteVoxels(volume, glm::ivec3(0), volume.dims, source);
    requireUsableGeometry(volume.dims, volume.spacing, volume.origin, volume.range, source);
}

void requireUsableValues(const Volume& box, const VoxelBox& stored, glm::ivec3 dims, const std::string& source) {
    requireFiniteVoxels(box, stored.lo, dims, source);
    requireUsableGeometry(dims, box.spacing, box.origin, box.range, source);
}

void requireUsableValues(const SparseVolume& volume, const std::string& source) {
    if (volume.type == VoxelType::Float32) {
        if (volume.storedBricks() < volume.brickCount() && !std::isfinite(volume.background()))
            throw Error(source + ": the background is " + exactNumber(volume.background()) +
                        ": float volumes must hold finite values");
        // The first bad voxel in brick order, whatever the threads do.
        std::mutex mutex;
        std::optional<std::pair<std::size_t, glm::ivec3>> bad;
        volume.forEachStoredBrick([&](std::size_t b, int x0, int y0, int z0, int nx, int ny, int nz) {
            const float* p = volume.block<float>(b);
            for (int k = 0; k < nz; ++k)
                for (int j = 0; j < ny; ++j)
                    for (int i = 0; i < nx; ++i)
                        if (!std::isfinite(p[(k * SparseVolume::kBlock + j) * SparseVolume::kBlock + i])) {
                            const std::lock_guard lock(mutex);
                            if (!bad || b < bad->first) bad.emplace(b, glm::ivec3(x0 + i, y0 + j, z0 + k));
                            return;
                        }
        });
        if (bad) {
            const glm::ivec3 at = bad->second;
            throw Error(detail::nonFiniteVoxel(at, volume.dims, volume.value(at.x, at.y, at.z), source));
        }
    }
    requireUsableGeometry(volume.dims, volume.spacing, volume.origin, volume.range, source);
}

VolumeStorage parseVolumeStorage(std::string_view name, const std::string& what) {
    if (name == "dense") return VolumeStorage::Dense;
    if (name == "sparse") return VolumeStorage::Sparse;
    if (name == "auto") return VolumeStorage::Auto;
    throw Error(what + ": unknown storage '" + printable(name) + "' (expected dense, sparse or auto)");
}

std::string_view volumeStorageName(VolumeStorage storage) {
    return storage == VolumeStorage::Dense ? "dense" : storage == VolumeStorage::Sparse ? "sparse" : "auto";
}

Volume readRaw(const fs::path& path, const RawLayout& layout) {
    detail::requireRegularFile(path);
    detail::requireValidLayout(path, layout);
    Volume volume = detail::readVoxelData(
        path, {layout.dims, detail::storedTypeOf(layout.type), layout.order, layout.headerBytes, false});
    volume.spacing = layout.spacing;
    return volume;
}

namespace {

// A raw file checked against its layout as readRaw checks it: its voxel bytes.
std::uint64_t checkedRawFile(const fs::path& path, const RawLayout& layout) {
    detail::requireRegularFile(path);
    detail::requireValidLayout(path, layout);
    const detail::StoredVoxels stored = detail::storedVoxels(
        path, {layout.dims, detail::storedTypeOf(layout.type), layout.order, layout.headerBytes, false});
    detail::requireExactSize(path, stored);
    return stored.bytes;
}

}  // namespace

Volume readRawBox(const fs::path& path, const RawLayout& layout, const VoxelBox& box) {
    checkedRawFile(path, layout);
    for (int a = 0; a < 3; ++a)
        if (box.lo[a] < 0 || box.hi[a] > layout.dims[a] || box.lo[a] >= box.hi[a])
            throw Error(path.string() + ": the box of voxels " + dimsText(box.lo) + " to " + dimsText(box.hi) +
                        " is not inside " + dimsText(layout.dims));
    // The box's bytes checked against the limit, the message naming the file.
    Volume volume = detail::namingFileIfTooLarge(path, [&] { return Volume(box.size(), layout.type); });
    volume.spacing = layout.spacing;
    std::ifstream in(path, std::ios::binary);
    const std::size_t size = voxelSize(layout.type);
    const std::size_t rowBytes = static_cast<std::size_t>(box.size().x) * size;
    for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y) {
            const std::uint64_t voxel = (static_cast<std::uint64_t>(z) * layout.dims.y + y) * layout.dims.x + box.lo.x;
            in.seekg(static_cast<std::streamoff>(layout.headerBytes + voxel * size));
            const std::size_t at = volume.index(0, y - box.lo.y, z - box.lo.z) * size;
            in.read(reinterpret_cast<char*>(volume.bytes.data() + at), static_cast<std::streamsize>(rowBytes));
            if (!in) throw Error(path.string() + ": read failed");
        }
    if (layout.order != nativeByteOrder()) reverseEachVoxel(volume.bytes, size);
    return volume;
}

ValueRange rawValueRange(const fs::path& path, const RawLayout& layout, const std::string& volumeName) {
    checkedRawFile(path, layout);
    const std::size_t size = voxelSize(layout.type);
    const glm::ivec3 dims = layout.dims;
    // A box of about a million voxels at a time, in the file's order: whole rows of one plane, or a run of one row
    // where a row is longer.
    constexpr int kChunkVoxels = 1 << 20;
    const int runX = std::min(dims.x, kChunkVoxels), runY = runX < dims.x ? 1 : std::max(1, kChunkVoxels / dims.x);
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(layout.headerBytes));
    ValueRange range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    Volume chunk;
    chunk.type = layout.type;
    const std::string source = volumeName.empty() ? path.string() : volumeName;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; y += runY)
            for (int x = 0; x < dims.x; x += runX) {
                chunk.dims = glm::ivec3(std::min(runX, dims.x - x), std::min(runY, dims.y - y), 1);
                chunk.bytes.resize(chunk.voxelCount() * size);
                in.read(reinterpret_cast<char*>(chunk.bytes.data()), static_cast<std::streamsize>(chunk.bytes.size()));
                if (!in) throw Error(path.string() + ": read failed");
                if (layout.order != nativeByteOrder()) reverseEachVoxel(chunk.bytes, size);
                const ValueRange r = detail::boxValueRange(chunk, {x, y, z}, dims, source);
                range.lo = std::min(range.lo, r.lo);
                range.hi = std::max(range.hi, r.hi);
            }
    return range;
}

void writeRaw(const fs::path& path, const Volume& volume, ByteOrder order) {
    std::vector<std::byte> swapped;
    writeTextFile(path, detail::rawBytes(path, volume, order, swapped));
}

std::optional<RawLayout> layoutFromFileName(const fs::path& path) {
    const std::string stem = path.stem().string();
    const std::size_t typeSeparator = stem.rfind('_');
    if (typeSeparator == std::string::npos || typeSeparator == 0) return std::nullopt;
    const std::size_t dimsSeparator = stem.rfind('_', typeSeparator - 1);
    const std::size_t dimsBegin = dimsSeparator == std::string::npos ? 0 : dimsSeparator + 1;
    const auto dims = parseDimsToken(std::string_view(stem).substr(dimsBegin, typeSeparator - dimsBegin));
    if (!dims) return std::nullopt;
    RawLayout layout;
    layout.dims = *dims;
    layout.type = parseVoxelType(stem.substr(typeSeparator + 1), path.string());
    return layout;
}

bool describesItsLayout(const fs::path& path) {
    const std::string extension = detail::toLower(path.extension().string());
    return extension == ".nhdr" || extension == ".nrrd" || extension == ".dat" || extension == ".vdb" ||
           extension == ".mhd" || extension == ".mha" || extension == ".tif" || extension == ".tiff";
}

std::optional<RawLayout> rawLayoutOf(const fs::path& path, const std::optional<RawLayout>& requested) {
    if (describesItsLayout(path)) {
        if (requested)
            throw Error(path.string() + ": dims and voxel type are for raw files; a " +
                        detail::toLower(path.extension().string()) + " file describes its own layout");
        return std::nullopt;
    }
    if (requested) return requested;
    if (const auto named = layoutFromFileName(path)) return named;
    throw Error(path.string() +
                ": raw file of unknown layout: give its dims and voxel type (--dims X,Y,Z "
                "--type uint8|uint16|float32) or name it NAME_XxYxZ_TYPE.raw");
}

Volume readVolume(const fs::path& path, const std::optional<RawLayout>& rawLayout) {
    detail::requireRegularFile(path);
    const std::string extension = detail::toLower(path.extension().string());
    const std::optional<RawLayout> raw = rawLayoutOf(path, rawLayout);
    const auto read = [&] {
        if (raw) return readRaw(path, *raw);
        if (const std::optional<detail::HeaderVoxels> header = detail::headerVoxels(path))
            return detail::readHeaderVoxels(path, *header);
        if (extension == ".tif" || extension == ".tiff") return detail::readTiffStack(path);
        return readVdb(path);
    };
    Volume volume = detail::namingFileIfTooLarge(path, read);
    requireUsableValues(volume, path.string());
    return volume;
}

void writeVolume(const fs::path& path, const Volume& volume) {
    const std::string extension = detail::toLower(path.extension().string());
    if (extension == ".vdb") return writeVdb(path, volume);
    if (extension == ".nhdr" || extension == ".nrrd") return detail::writeNrrd(path, volume);
    if (extension == ".dat") return detail::writeInviwoDat(path, volume);
    if (extension == ".raw") return writeRaw(path, volume);
    throw Error(path.string() + ": cannot write '" + extension + "' files (expected .vdb, .nhdr, .nrrd, .dat or .raw)");
}

std::vector<fs::path> filesWrittenBy(const fs::path& path) {
    const std::string extension = detail::toLower(path.extension().string());
    if (extension == ".nhdr" || extension == ".dat") return {detail::rawFileBeside(path), path};
    return {path};
}

std::vector<fs::path> filesReadBy(const fs::path& path) {
    std::optional<detail::HeaderVoxels> header;
    try {
        header = detail::headerVoxels(path);
    } catch (const Error&) {
        // A header that cannot be parsed names no data file; reading the volume says what is wrong with it.
    }
    if (header && header->dataPath != path) return {path, header->dataPath};
    return {path};
}

}  // namespace vri
