#include "libvri/io/volume_read_options.h"

#include "libvri/io/volume_formats.h"
#include "libvri/util/error.h"
#include "libvri/util/parse.h"

namespace vri {

std::optional<RawLayout> requestedRawLayout(const std::filesystem::path& input, const VolumeReadOptions& options) {
    const std::string& dims = options.dims;
    const bool rawGiven = !dims.empty() || !options.type.empty() || options.byteOrder || options.headerBytes;
    if (options.grid && (rawGiven || input.extension() != ".vdb")) throw Error("--grid applies to .vdb input only");
    if (!rawGiven) return std::nullopt;
    if (dims.empty() != options.type.empty()) throw Error("--dims and --type go together");
    std::optional<RawLayout> layout;
    if (dims.empty()) {
        layout = layoutFromFileName(input);
        if (!layout)
            throw Error(input.string() + ": --byte-order and --header-bytes need --dims and --type "
                                         "(the file name does not give them)");
    } else {
        layout = RawLayout{parseDims(dims, "--dims"), parseVoxelType(options.type, "--type")};
    }
    if (options.byteOrder) {
        const std::string& order = *options.byteOrder;
        if (order != "little" && order != "big") throw Error("--byte-order: expected little or big, got '" + order + "'");
        layout->order = order == "big" ? ByteOrder::Big : ByteOrder::Little;
    }
    const long long headerBytes = options.headerBytes.value_or(0);
    if (headerBytes < 0) throw Error("--header-bytes: expected a byte count, got " + std::to_string(headerBytes));
    layout->headerBytes = static_cast<std::size_t>(headerBytes);
    return layout;
}

namespace {

// --spacing, when given, over what the file says.
template <class V>
void overrideSpacing(V& volume, const VolumeReadOptions& options) {
    if (options.spacing.empty()) return;
    volume.spacing = parseVec3(options.spacing, "--spacing");
    if (!(volume.spacing.x > 0 && volume.spacing.y > 0 && volume.spacing.z > 0))
        throw Error("--spacing: expected positive numbers, got '" + options.spacing + "'");
    requireUsableValues(volume, "--spacing " + options.spacing);
}

}  // namespace

Volume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options) {
    const std::optional<RawLayout> layout = requestedRawLayout(input, options);
    Volume volume = options.grid ? readVdb(input, *options.grid) : readVolume(input, layout);
    overrideSpacing(volume, options);
    return volume;
}

LoadedVolume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options, VolumeStorage storage) {
    const std::optional<RawLayout> layout = requestedRawLayout(input, options);
    if (!layout && detail::toLower(input.extension().string()) == ".vdb") {
        LoadedVolume loaded = readVdb(input, options.grid, storage);
        if (loaded.sparse) {
            requireUsableValues(*loaded.sparse, input.string());
            overrideSpacing(*loaded.sparse, options);
        } else {
            requireUsableValues(*loaded.dense, input.string());
            overrideSpacing(*loaded.dense, options);
        }
        return loaded;
    }
    auto dense = std::make_shared<Volume>(readVolume(input, options));
    if (storage != VolumeStorage::Sparse) return {std::move(dense), nullptr};
    auto sparse = std::make_shared<SparseVolume>(
        detail::namingFileIfOutOfMemory(input, [&] { return SparseVolume::fromDense(*dense); }));
    return {nullptr, std::move(sparse)};
}

namespace {

// One brick of a NRRD whose voxels lie in its data file as vri keeps them (raw encoding; uint8, uint16 or
// float32), read as a raw file's is: its stored box alone. nullopt for any other file (not NRRD, gzip, a type
// vri converts), which the caller reads whole.
std::optional<BrickVolume> nrrdBrick(const std::filesystem::path& input, const VolumeReadOptions& options,
                                     glm::ivec3 counts, glm::ivec3 brick, const std::optional<ValueRange>& range) {
    const std::string extension = detail::toLower(input.extension().string());
    if (extension != ".nrrd" && extension != ".nhdr") return std::nullopt;
    const detail::NrrdVoxels nrrd = detail::nrrdVoxels(input);
    const VoxelType type = detail::volumeTypeFor(nrrd.data.type);
    if (nrrd.data.gzip || detail::storedTypeOf(type) != nrrd.data.type) return std::nullopt;
    RawLayout layout{nrrd.data.dims, type, nrrd.data.order, nrrd.spacing, 0};
    const auto inHeader = [&](auto read) {  // the data file's message, after the header that names it
        try {
            return read();
        } catch (const Error& e) {
            if (nrrd.dataPath == input) throw;
            throw Error(input.string() + ": data file " + e.what());
        }
    };
    // The voxels as the file's last bytes: the rest is header (the size check then names both sizes).
    std::error_code ec;
    const std::uintmax_t fileBytes = std::filesystem::file_size(nrrd.dataPath, ec);
    // (A product past 2^64 leaves it 0 here: the read then refuses the layout, naming the file.)
    const std::optional<std::uint64_t> voxelBytes = checkedProduct(
        {std::uint64_t(layout.dims.x), std::uint64_t(layout.dims.y), std::uint64_t(layout.dims.z), voxelSize(type)});
    layout.headerBytes = static_cast<std::size_t>(
        nrrd.data.offset.value_or(!ec && voxelBytes && fileBytes > *voxelBytes ? fileBytes - *voxelBytes : 0));
    const BrickGrid grid(layout.dims, counts);
    grid.requireBrick(brick, "--brick");
    BrickVolume b{grid, brick, inHeader([&] { return readRawBox(nrrd.dataPath, layout, grid.storedBox(brick)); })};
    if (nrrd.origin) b.voxels.origin = *nrrd.origin;
    b.voxels.range = range ? range : nrrd.range ? nrrd.range : fixedNormalisationRange(type, std::nullopt);
    if (!b.voxels.range) b.voxels.range = inHeader([&] { return rawValueRange(nrrd.dataPath, layout); });
    overrideSpacing(b.voxels, options);
    requireUsableValues(b.voxels, input.string());
    return b;
}

}  // namespace

BrickVolume readBrick(const std::filesystem::path& input, const VolumeReadOptions& options, glm::ivec3 counts,
                      glm::ivec3 brick, const std::optional<ValueRange>& range) {
    if (options.grid) throw Error("--brick: reads dense volumes (raw, NRRD, ...), not a .vdb grid");
    const std::optional<RawLayout> layout = rawLayoutOf(input, requestedRawLayout(input, options));
    if (!layout) {
        if (std::optional<BrickVolume> b = nrrdBrick(input, options, counts, brick, range)) return std::move(*b);
        // Any other format that describes itself: read whole, then cut.
        Volume whole = readVolume(input, options);
        if (range) whole.range = *range;
        requireUsableValues(whole, input.string());
        return cutBrick(whole, BrickGrid(whole.dims, counts), brick);
    }
    const BrickGrid grid(layout->dims, counts);
    grid.requireBrick(brick, "--brick");
    BrickVolume b{grid, brick, readRawBox(input, *layout, grid.storedBox(brick))};
    b.voxels.range = range ? range : fixedNormalisationRange(layout->type, std::nullopt);
    if (!b.voxels.range) b.voxels.range = rawValueRange(input, *layout);
    overrideSpacing(b.voxels, options);
    requireUsableValues(b.voxels, input.string());
    return b;
}

}  // namespace vri
