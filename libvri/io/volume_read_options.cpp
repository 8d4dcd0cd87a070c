#include "libvri/io/volume_read_options.h"

#include <functional>
#include <string>

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

// --spacing, when given, over what the file says, then the box it makes checked, for a volume of `dims` (a
// brick's: its whole volume's); the values were checked as they were read, and --spacing changes none.
template <class V>
void overrideSpacing(V& volume, const VolumeReadOptions& options, glm::ivec3 dims) {
    if (options.spacing.empty()) return;
    volume.spacing = parseVec3(options.spacing, "--spacing");
    if (!(volume.spacing.x > 0 && volume.spacing.y > 0 && volume.spacing.z > 0))
        throw Error("--spacing: expected positive numbers, got '" + options.spacing + "'");
    requireUsableGeometry(dims, volume.spacing, volume.origin, volume.range, "--spacing " + options.spacing);
}

}  // namespace

Volume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options) {
    const std::optional<RawLayout> layout = requestedRawLayout(input, options);
    Volume volume = options.grid ? readVdb(input, *options.grid) : readVolume(input, layout);
    overrideSpacing(volume, options, volume.dims);
    return volume;
}

LoadedVolume readVolume(const std::filesystem::path& input, const VolumeReadOptions& options, VolumeStorage storage) {
    const std::optional<RawLayout> layout = requestedRawLayout(input, options);
    if (!layout && detail::toLower(input.extension().string()) == ".vdb") {
        LoadedVolume loaded = readVdb(input, options.grid, storage);
        if (loaded.sparse) {
            requireUsableValues(*loaded.sparse, input.string());
            overrideSpacing(*loaded.sparse, options, loaded.sparse->dims);
        } else {
            requireUsableValues(*loaded.dense, input.string());
            overrideSpacing(*loaded.dense, options, loaded.dense->dims);
        }
        return loaded;
    }
    auto dense = std::make_shared<Volume>(readVolume(input, options));
    if (storage != VolumeStorage::Sparse) return {std::move(dense), nullptr};
    auto sparse = std::make_shared<SparseVolume>(
        detail::namingFileIfTooLarge(input, [&] { return SparseVolume::fromDense(*dense); }));
    return {nullptr, std::move(sparse)};
}

namespace {

// What a brick is read from without the whole volume: the volume's dims and voxel type, what a header adds, its
// box of voxels read alone, and the min..max of its values scanned a part at a time.
struct BrickSource {
    glm::ivec3 dims{0};
    VoxelType type = VoxelType::UInt8;
    std::optional<glm::dvec3> origin;
    std::optional<ValueRange> range;
    std::function<Volume(const VoxelBox&)> readBox;
    std::function<ValueRange()> scanRange;
};

// A raw file, an Inviwo .dat's raw file, or the data of a NRRD or MetaImage stored as vri keeps them
// (uncompressed; uint8, uint16 or float32), read by offset with what a header adds and its messages after the
// header's; a TIFF stack of such pages, by its pages' rows. nullopt for any other file (compressed, a type vri
// converts, .vdb), which a brick reads whole.
std::optional<BrickSource> brickSource(const std::filesystem::path& input, const VolumeReadOptions& options) {
    // `file`'s voxels laid out as `layout`, named after `input` where that is a header (`entry`: its word for
    // the data file).
    const auto byOffset = [&input](const std::filesystem::path& file, const RawLayout& layout, std::string_view entry) {
        const auto naming = [input, file, entry](auto read) { return detail::namingHeader(input, file, read, entry); };
        return BrickSource{
            layout.dims,
            layout.type,
            std::nullopt,
            std::nullopt,
            [=](const VoxelBox& box) { return naming([&] { return readRawBox(file, layout, box); }); },
            [=] { return naming([&] { return rawValueRange(file, layout, input.string()); }); }};
    };
    if (const std::optional<RawLayout> layout = rawLayoutOf(input, requestedRawLayout(input, options)))
        return byOffset(input, *layout, {});
    if (const std::optional<detail::HeaderVoxels> header = detail::headerVoxels(input)) {
        if (header->data.gzip || !detail::keptAsStored(header->data.type)) return std::nullopt;
        RawLayout layout{header->data.dims, detail::volumeTypeFor(header->data.type), header->data.order,
                         header->spacing, 0};
        // Where the data begin (the file's last bytes, for a header size of -1); the read checks the file's size.
        layout.headerBytes = static_cast<std::size_t>(detail::namingHeader(
            input, header->dataPath, [&] { return detail::storedVoxels(header->dataPath, header->data).offset; },
            header->entry));
        BrickSource source = byOffset(header->dataPath, layout, header->entry);
        source.origin = header->origin;
        source.range = header->range;
        return source;
    }
    const std::string extension = detail::toLower(input.extension().string());
    if (extension != ".tif" && extension != ".tiff") return std::nullopt;
    const detail::TiffStackShape shape = detail::tiffStackShape(input);
    if (!detail::keptAsStored(shape.type)) return std::nullopt;
    return BrickSource{{shape.width, shape.height, shape.pages},
                       detail::volumeTypeFor(shape.type),
                       std::nullopt,
                       std::nullopt,
                       [=](const VoxelBox& box) { return detail::readTiffStackBox(input, box); },
                       [=] { return detail::tiffStackValueRange(input); }};
}

}  // namespace

std::optional<VolumeShape> brickedShape(const std::filesystem::path& input, const VolumeReadOptions& options) {
    if (const std::optional<BrickSource> source = brickSource(input, options))
        return VolumeShape{source->dims, source->type};
    return std::nullopt;
}

BrickVolume readBrick(const std::filesystem::path& input, const VolumeReadOptions& options, glm::ivec3 counts,
                      glm::ivec3 brick, const std::optional<ValueRange>& range) {
    if (options.grid) throw Error("--brick: reads dense volumes (raw, NRRD, ...), not a .vdb grid");
    const std::optional<BrickSource> source = brickSource(input, options);
    if (!source) {  // read whole, then cut
        Volume whole = readVolume(input, options);
        if (range) whole.range = *range;
        requireUsableValues(whole, input.string());
        return cutBrick(whole, BrickGrid(whole.dims, counts), brick);
    }
    const BrickGrid grid(source->dims, counts);
    grid.requireBrick(brick, "--brick");
    BrickVolume b{grid, brick, source->readBox(grid.storedBox(brick))};
    if (source->origin) b.voxels.origin = *source->origin;
    b.voxels.range = range           ? range
                     : source->range ? source->range
                                     : fixedNormalisationRange(source->type, std::nullopt);
    // A NaN named as the whole read names it: by the volume's name and its place in the volume.
    if (!b.voxels.range) b.voxels.range = source->scanRange();
    // Checked as the whole volume is, in its order (the file's values, then --spacing's box): its box, a voxel
    // named by its place in it.
    requireUsableValues(b.voxels, grid.storedBox(brick), grid.dims(), input.string());
    overrideSpacing(b.voxels, options, grid.dims());
    return b;
}

}  // namespace vri
