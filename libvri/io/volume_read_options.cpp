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

BrickVolume readBrick(const std::filesystem::path& input, const VolumeReadOptions& options, glm::ivec3 counts,
                      glm::ivec3 brick, const std::optional<ValueRange>& range) {
    if (options.grid) throw Error("--brick: reads dense volumes (raw, NRRD, ...), not a .vdb grid");
    const std::optional<RawLayout> layout = rawLayoutOf(input, requestedRawLayout(input, options));
    if (!layout) {  // a format that describes itself: read whole, then cut
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
