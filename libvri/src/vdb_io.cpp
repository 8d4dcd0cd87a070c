// OpenVDB .vdb files. The only translation unit that includes OpenVDB: its headers cost about
// half a gigabyte of compiler memory, so nothing else may pull them in.
//
// A vri volume is stored as one sparse grid named "density": float32 in a FloatGrid, uint8 and
// uint16 in an Int32Grid (OpenVDB registers no 8- or 16-bit grid types). Background 0, and voxels
// equal to it are not stored. Voxel (i,j,k) sits at index (i,j,k); the transform maps index to
// world as origin + index * spacing. Grid metadata record what the sparse grid cannot: the voxel
// type, the dense dims (trailing empty slabs have no active voxels) and the normalisation range.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <sstream>
#include <type_traits>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "vri/atomic_file.h"
#include "vri/checked_size.h"
#include "vri/error.h"
#include "vri/volume_io.h"
#include "volume_formats.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

constexpr const char* kGridName = "density";
constexpr const char* kVoxelTypeKey = "vri_voxel_type";
constexpr const char* kDimsKey = "vri_dims";
constexpr const char* kRangeKey = "vri_range";

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::CoordBBox indexBox(glm::ivec3 dims) {
    return {openvdb::Coord(0, 0, 0), openvdb::Coord(dims.x - 1, dims.y - 1, dims.z - 1)};
}

// copyFromDense drops the values it finds approximately equal to the background: besides 0 that
// is -0.0f (== 0.0f) and NaN (every comparison with it is false). Put those voxels back so that
// the round trip stays bitwise exact.
void restoreBackgroundLookalikes(const Volume& volume, openvdb::FloatGrid& grid) {
    const float* values = volume.data<float>();
    auto accessor = grid.getAccessor();
    for (int z = 0; z < volume.dims.z; ++z)
        for (int y = 0; y < volume.dims.y; ++y)
            for (int x = 0; x < volume.dims.x; ++x) {
                const float value = values[volume.index(x, y, z)];
                if ((value == 0.0f && std::signbit(value)) || std::isnan(value))
                    accessor.setValueOn(openvdb::Coord(x, y, z), value);
            }
}

template <class T>
openvdb::GridBase::Ptr sparseGrid(const Volume& volume) {
    using GridT = std::conditional_t<std::is_same_v<T, float>, openvdb::FloatGrid, openvdb::Int32Grid>;
    using ValueT = typename GridT::ValueType;
    typename GridT::Ptr grid = GridT::create(ValueT(0));
    const openvdb::tools::Dense<const T, openvdb::tools::LayoutXYZ> dense(indexBox(volume.dims), volume.data<T>());
    openvdb::tools::copyFromDense(dense, *grid, ValueT(0), /*serial=*/false);
    if constexpr (std::is_same_v<T, float>) restoreBackgroundLookalikes(volume, *grid);
    return grid;
}

openvdb::GridBase::Ptr toGrid(const Volume& volume) {
    openvdb::GridBase::Ptr grid =
        dispatchVoxelType(volume.type, [&](auto t) { return sparseGrid<decltype(t)>(volume); });
    grid->setName(kGridName);
    grid->insertMeta(kVoxelTypeKey, openvdb::StringMetadata(std::string(voxelTypeName(volume.type))));
    grid->insertMeta(kDimsKey, openvdb::Vec3IMetadata(openvdb::Vec3i(volume.dims.x, volume.dims.y, volume.dims.z)));
    if (volume.range)
        grid->insertMeta(kRangeKey, openvdb::Vec2DMetadata(openvdb::Vec2d(volume.range->lo, volume.range->hi)));
    const glm::dvec3 s = volume.spacing;
    const glm::dvec3 o = volume.origin;
    grid->setTransform(std::make_shared<openvdb::math::Transform>(std::make_shared<openvdb::math::ScaleTranslateMap>(
        openvdb::Vec3d(s.x, s.y, s.z), openvdb::Vec3d(o.x, o.y, o.z))));
    return grid;
}

template <class T, class GridT>
void copyToVolume(const openvdb::GridBase& grid, const openvdb::CoordBBox& box, Volume& volume) {
    openvdb::tools::Dense<T, openvdb::tools::LayoutXYZ> dense(box, volume.data<T>());
    openvdb::tools::copyToDense(static_cast<const GridT&>(grid), dense, /*serial=*/false);
}

std::string gridDescription(const openvdb::GridBase& grid) {
    return "grid '" + grid.getName() + "' (" + grid.valueType() + ")";
}

std::string boxText(const openvdb::CoordBBox& box) {
    const auto coord = [](const openvdb::Coord& c) {
        return "(" + std::to_string(c.x()) + "," + std::to_string(c.y()) + "," + std::to_string(c.z()) + ")";
    };
    return coord(box.min()) + ".." + coord(box.max());
}

// A sparse grid stores nothing for background voxels and one tile for a constant region, so its file
// says little about its dense size; metadata claiming 1024^3 voxels in a 10 KB file is still far more
// likely an error (or an attack) than a volume. Unless VRI_MAX_BYTES states the limit, a dense
// volume may take 1024 times the file's bytes, or 256 MiB whatever the file.
constexpr std::uint64_t kPlausibleExpansion = 1024;
constexpr std::uint64_t kAlwaysPlausibleBytes = std::uint64_t(1) << 28;

// The dense dims of `box`, checked against the byte limit and the file's size before anything is allocated.
glm::ivec3 denseDims(const fs::path& path, const std::string& source, const openvdb::CoordBBox& box, VoxelType type) {
    std::uint64_t extent[3];
    for (int axis = 0; axis < 3; ++axis) {
        extent[axis] = static_cast<std::uint64_t>(std::int64_t(box.max()[axis]) - std::int64_t(box.min()[axis]) + 1);
        if (extent[axis] > std::uint64_t(std::numeric_limits<int>::max()))
            throw Error(path.string() + ": " + source + " " + boxText(box) + " is wider than " +
                        std::to_string(std::numeric_limits<int>::max()) + " voxels");
    }
    const std::string what = path.string() + ": " + source + " " + std::to_string(extent[0]) + "x" +
                             std::to_string(extent[1]) + "x" + std::to_string(extent[2]) + " (" +
                             std::string(voxelTypeName(type)) + ")";
    const std::uint64_t bytes = checkedBytes(what, {extent[0], extent[1], extent[2], voxelSize(type)});
    const std::uint64_t fileBytes = fs::file_size(path);
    const std::uint64_t plausible =
        std::max(kAlwaysPlausibleBytes, checkedProduct({fileBytes, kPlausibleExpansion}).value_or(UINT64_MAX));
    if (bytes > plausible && !byteLimitIsExplicit())
        throw Error(what + ": needs " + std::to_string(bytes) + " bytes, limit " + std::to_string(plausible) +
                    " for a file of " + std::to_string(fileBytes) + " bytes (" + std::to_string(kPlausibleExpansion) +
                    " times its size or 256 MiB; set VRI_MAX_BYTES to allow more)");
    return {int(extent[0]), int(extent[1]), int(extent[2])};
}

Volume toVolume(const fs::path& path, const openvdb::GridBase& grid) {
    const openvdb::math::Transform& transform = grid.transform();
    const openvdb::Mat3d linear = transform.baseMap()->getAffineMap()->getMat4().getMat3();
    if (!transform.isLinear() || !openvdb::math::isDiagonal(linear) || linear(0, 0) <= 0 || linear(1, 1) <= 0 ||
        linear(2, 2) <= 0)
        throw Error(path.string() + ": " + gridDescription(grid) +
                    " has a rotated, flipped or non-linear transform; only axis-aligned grids are supported");

    const auto typeMeta = grid.getMetadata<openvdb::StringMetadata>(kVoxelTypeKey);
    const auto dimsMeta = grid.getMetadata<openvdb::Vec3IMetadata>(kDimsKey);
    const bool writtenByVri = typeMeta && dimsMeta;
    VoxelType type = VoxelType::Float32;
    openvdb::CoordBBox box;
    if (writtenByVri) {
        type = parseVoxelType(typeMeta->value(), path.string() + ": " + kVoxelTypeKey);
        const openvdb::Vec3i d = dimsMeta->value();
        if (d.x() < 1 || d.y() < 1 || d.z() < 1)
            throw Error(path.string() + ": " + kDimsKey + " must be positive");
        box = indexBox({d.x(), d.y(), d.z()});
        // vri writes voxel (i,j,k) at index (i,j,k): every active voxel lies inside the dims.
        const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
        if (!active.empty() && !box.isInside(active))
            throw Error(path.string() + ": " + kDimsKey + " " + std::to_string(d.x()) + "x" + std::to_string(d.y()) +
                        "x" + std::to_string(d.z()) + " does not contain the active voxels " + boxText(active));
    } else {
        box = grid.evalActiveVoxelBoundingBox();
        if (box.empty()) throw Error(path.string() + ": " + gridDescription(grid) + " has no active voxels");
    }

    Volume volume(denseDims(path, writtenByVri ? kDimsKey : "active voxels", box, type), type);
    const openvdb::Vec3d spacing = transform.voxelSize();
    const openvdb::Vec3d origin = transform.indexToWorld(box.min());
    volume.spacing = {spacing.x(), spacing.y(), spacing.z()};
    volume.origin = {origin.x(), origin.y(), origin.z()};
    if (const auto range = grid.getMetadata<openvdb::Vec2DMetadata>(kRangeKey); range && writtenByVri)
        volume.range = ValueRange{range->value().x(), range->value().y()};

    const bool isInt = grid.isType<openvdb::Int32Grid>();
    if (type == VoxelType::UInt8 && isInt) copyToVolume<std::uint8_t, openvdb::Int32Grid>(grid, box, volume);
    else if (type == VoxelType::UInt16 && isInt) copyToVolume<std::uint16_t, openvdb::Int32Grid>(grid, box, volume);
    else if (type == VoxelType::Float32 && grid.isType<openvdb::FloatGrid>())
        copyToVolume<float, openvdb::FloatGrid>(grid, box, volume);
    else if (type == VoxelType::Float32 && grid.isType<openvdb::DoubleGrid>() && !writtenByVri)
        copyToVolume<float, openvdb::DoubleGrid>(grid, box, volume);
    else if (type == VoxelType::Float32 && isInt && !writtenByVri)
        copyToVolume<float, openvdb::Int32Grid>(grid, box, volume);
    else
        throw Error(path.string() + ": " + gridDescription(grid) + " cannot hold " +
                    std::string(voxelTypeName(type)) + " voxels as its metadata claim");
    return volume;
}

bool isScalarGrid(const openvdb::GridBase& grid) {
    return grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>() ||
           grid.isType<openvdb::Int32Grid>();
}

std::string gridList(openvdb::io::File& file) {
    std::string names;
    const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    for (const openvdb::GridBase::Ptr& grid : *grids)
        names += (names.empty() ? "" : ", ") + gridDescription(*grid);
    return names.empty() ? "none" : names;
}

// io::File::write streams into an std::ofstream it never checks, so a full disk went unnoticed. The
// same bytes (header, grids and the offsets that let a reader load grids lazily, hence a seekable
// stream) are encoded into memory instead, and written through writeTextFile's checked writes.
class SeekableArchive : public openvdb::io::Archive {
public:
    void writeTo(std::ostream& out, const openvdb::GridPtrVec& grids) const {
        Archive::write(out, grids, /*seekable=*/true);
    }
};

}  // namespace

Volume readVdb(const fs::path& path, const std::optional<std::string>& gridName) {
    detail::requireRegularFile(path);
    initializeOpenVdb();
    try {
        openvdb::io::File file(path.string());
        file.open(/*delayLoad=*/false);
        openvdb::GridBase::Ptr grid;
        if (gridName) {
            if (!file.hasGrid(*gridName))
                throw Error(path.string() + ": no grid named '" + *gridName + "' (grids: " + gridList(file) + ")");
            grid = file.readGrid(*gridName);
            if (!isScalarGrid(*grid))
                throw Error(path.string() + ": " + gridDescription(*grid) + " is not a float, double or int32 grid");
        } else {
            const openvdb::GridPtrVecPtr candidates = file.readAllGridMetadata();
            for (const openvdb::GridBase::Ptr& candidate : *candidates)
                if (isScalarGrid(*candidate)) {
                    grid = file.readGrid(candidate->getName());
                    break;
                }
            if (!grid)
                throw Error(path.string() + ": no float, double or int32 grid (grids: " + gridList(file) + ")");
        }
        file.close();
        return toVolume(path, *grid);
    } catch (const openvdb::Exception& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

void writeVdb(const fs::path& path, const Volume& volume) {
    if (volume.bytes.size() != volume.byteCount() || volume.voxelCount() == 0)
        throw Error(path.string() + ": volume holds " + std::to_string(volume.bytes.size()) +
                    " bytes, which does not match its dims");
    initializeOpenVdb();
    std::ostringstream encoded;
    try {
        SeekableArchive().writeTo(encoded, {toGrid(volume)});
    } catch (const openvdb::Exception& e) {
        throw Error(path.string() + ": " + e.what());
    }
    if (!encoded) throw Error(path.string() + ": cannot encode the grid");
    writeTextFile(path, encoded.view());
}

}  // namespace vri
