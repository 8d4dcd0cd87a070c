// OpenVDB .vdb files, the functions of vri's OpenVDB module (vdb_module.h). The only translation unit that
// includes OpenVDB: its headers cost about half a gigabyte of compiler memory, so nothing else may pull them in.
//
// A vri volume is stored the way other programs expect a density: one FloatGrid named "density" of
// class fog volume, holding the raw voxel values (float holds every uint8 and uint16 value exactly).
// Background 0, and voxels equal to it are not stored. Voxel (i,j,k) sits at index (i,j,k), and the
// transform maps an index to the world position of that voxel's centre (OpenVDB's meaning of an index,
// and vri's cell-centred reading of the box): corner + (index + 1/2) * spacing. Grid metadata record what
// the sparse grid cannot: the voxel type, the dense dims (trailing empty slabs have no active voxels),
// the normalisation range and vri_format_version (vdb_grid_layout.h; version 1 files still read).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <mutex>
#include <sstream>
#include <type_traits>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "libvri/io/io_module.h"
#include "libvri/io/vdb_grid_layout.h"
#include "libvri/io/vdb_module.h"
#include "libvri/io/volume_formats.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/checked_size.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

constexpr const char* kGridName = "density";
constexpr const char* kVoxelTypeKey = "vri_voxel_type";
constexpr const char* kDimsKey = "vri_dims";
constexpr const char* kRangeKey = "vri_range";
constexpr const char* kFormatVersionKey = "vri_format_version";

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
openvdb::FloatGrid::Ptr sparseGrid(const Volume& volume) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    const openvdb::tools::Dense<const T, openvdb::tools::LayoutXYZ> dense(indexBox(volume.dims), volume.data<T>());
    openvdb::tools::copyFromDense(dense, *grid, 0.0f, /*serial=*/false);
    if constexpr (std::is_same_v<T, float>) restoreBackgroundLookalikes(volume, *grid);
    return grid;
}

openvdb::GridBase::Ptr toGrid(const Volume& volume) {
    openvdb::FloatGrid::Ptr grid =
        dispatchVoxelType(volume.type, [&](auto t) { return sparseGrid<decltype(t)>(volume); });
    grid->setName(kGridName);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->insertMeta(kVoxelTypeKey, openvdb::StringMetadata(std::string(voxelTypeName(volume.type))));
    grid->insertMeta(kDimsKey, openvdb::Vec3IMetadata(openvdb::Vec3i(volume.dims.x, volume.dims.y, volume.dims.z)));
    grid->insertMeta(kFormatVersionKey, openvdb::Int32Metadata(detail::kVdbFormatVersion));
    if (volume.range)
        grid->insertMeta(kRangeKey, openvdb::Vec2DMetadata(openvdb::Vec2d(volume.range->lo, volume.range->hi)));
    const glm::dvec3 s = volume.spacing;
    const glm::dvec3 centre0 = volume.origin + 0.5 * s;
    // Scale first, then translate: Transform's constructor simplifies a ScaleTranslateMap through its
    // affine matrix and recovers the scale as (translation + scale) - translation, which rounds; the
    // translation added afterwards keeps both exactly.
    auto transform = std::make_shared<openvdb::math::Transform>(
        std::make_shared<openvdb::math::ScaleMap>(openvdb::Vec3d(s.x, s.y, s.z)));
    transform->postTranslate(openvdb::Vec3d(centre0.x, centre0.y, centre0.z));
    grid->setTransform(transform);
    return grid;
}

std::string gridDescription(const openvdb::GridBase& grid) {
    return "grid '" + grid.getName() + "' (" + grid.valueType() + ")";
}

// Every value a grid can yield (its background and each active voxel or tile) must be one that T holds
// exactly for integer T, or within float's range for float: copyToDense converts with a plain cast,
// undefined beyond the target's range. A uint8 volume stored as floats must hold whole numbers 0..255.
template <class T, class GridT>
void requireRepresentable(const fs::path& path, const GridT& grid) {
    const std::string expected = std::is_same_v<T, std::uint8_t>    ? "a whole number 0..255 (uint8)"
                                 : std::is_same_v<T, std::uint16_t> ? "a whole number 0..65535 (uint16)"
                                                                    : "within float32's range";
    const auto refuse = [&](double value, const std::string& where) {
        throw Error(path.string() + ": " + gridDescription(grid) + " holds " + exactNumber(value) + where +
                    ", expected " + expected);
    };
    const auto fits = [](double value) {
        if constexpr (std::is_integral_v<T>)
            return value >= 0.0 && value <= double(std::numeric_limits<T>::max()) && value == std::floor(value);
        else
            return !std::isfinite(value) || std::abs(value) <= double(std::numeric_limits<float>::max());
    };
    if (!fits(double(grid.background()))) refuse(double(grid.background()), " as its background");
    for (auto it = grid.cbeginValueOn(); it; ++it)
        if (!fits(double(*it))) {
            const openvdb::Coord c = it.getCoord();
            refuse(double(*it), " at index (" + std::to_string(c.x()) + "," + std::to_string(c.y()) + "," +
                                    std::to_string(c.z()) + ")");
        }
}

template <class T, class GridT>
void copyToVolume(const fs::path& path, const openvdb::GridBase& grid, const openvdb::CoordBBox& box, Volume& volume) {
    const GridT& typed = static_cast<const GridT&>(grid);
    if constexpr (!std::is_same_v<T, typename GridT::ValueType>) requireRepresentable<T>(path, typed);
    openvdb::tools::Dense<T, openvdb::tools::LayoutXYZ> dense(box, volume.data<T>());
    openvdb::tools::copyToDense(typed, dense, /*serial=*/false);
}

// Why `bytes` sized from the file's metadata are too many: over the byte limit, or over the plausible
// expansion of the file's size (checked_size.h); nullopt when they are not.
std::optional<std::string> sizeRefusal(const fs::path& path, const std::string& what,
                                       std::initializer_list<std::uint64_t> factors) {
    try {
        checkedUnpackedBytes(what, factors, fs::file_size(path), "a file", kPlausibleSparseExpansion);
        return std::nullopt;
    } catch (const Error& e) {
        return e.what();
    }
}

std::string boxDescription(const fs::path& path, const std::string& source, glm::ivec3 dims, VoxelType type) {
    return path.string() + ": " + source + " " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
           std::to_string(dims.z) + " (" + std::string(voxelTypeName(type)) + ")";
}

// The dense volume's bytes, checked against the byte limit and the file's size before anything is
// allocated; nullopt when they pass.
std::optional<std::string> denseSizeRefusal(const fs::path& path, const std::string& source, glm::ivec3 dims,
                                            VoxelType type) {
    return sizeRefusal(path, boxDescription(path, source, dims, type),
                       {std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z), voxelSize(type)});
}

detail::VdbGridFacts gridFacts(const openvdb::GridBase& grid) {
    detail::VdbGridFacts facts;
    facts.description = gridDescription(grid);
    facts.valueType = grid.isType<openvdb::Int32Grid>()    ? detail::VdbValueType::Int32
                      : grid.isType<openvdb::Int64Grid>()  ? detail::VdbValueType::Int64
                      : grid.isType<openvdb::DoubleGrid>() ? detail::VdbValueType::Double
                                                           : detail::VdbValueType::Float;
    const openvdb::math::Transform& transform = grid.transform();
    facts.linearTransform = transform.isLinear();
    const openvdb::Mat3d linear = transform.baseMap()->getAffineMap()->getMat4().getMat3();
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) facts.linear[column][row] = linear(row, column);
    if (const auto type = grid.getMetadata<openvdb::StringMetadata>(kVoxelTypeKey)) facts.voxelTypeMeta = type->value();
    if (const auto dims = grid.getMetadata<openvdb::Vec3IMetadata>(kDimsKey))
        facts.dimsMeta = glm::ivec3(dims->value().x(), dims->value().y(), dims->value().z());
    if (const auto range = grid.getMetadata<openvdb::Vec2DMetadata>(kRangeKey))
        facts.rangeMeta = glm::dvec2(range->value().x(), range->value().y());
    if (const auto version = grid.getMetadata<openvdb::Int32Metadata>(kFormatVersionKey))
        facts.formatVersionMeta = version->value();
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (!active.empty()) {
        facts.activeMin = glm::ivec3(active.min().x(), active.min().y(), active.min().z());
        facts.activeMax = glm::ivec3(active.max().x(), active.max().y(), active.max().z());
    }
    return facts;
}

// What a grid becomes: its layout, the index box that is read, and where the box sits in the world.
struct GridPlacement {
    detail::VdbVolumeLayout layout;
    openvdb::CoordBBox box;
    std::string source;  // where the dims come from, for messages
    glm::dvec3 spacing, origin;
};

GridPlacement placement(const fs::path& path, const openvdb::GridBase& grid) {
    const detail::VdbGridFacts facts = gridFacts(grid);
    GridPlacement p{detail::vdbVolumeLayout(path.string(), facts), {}, {}, {}, {}};
    const detail::VdbVolumeLayout& layout = p.layout;
    p.source = facts.voxelTypeMeta && facts.dimsMeta ? kDimsKey : "active voxels";
    const openvdb::Coord boxMin(layout.boxMin.x, layout.boxMin.y, layout.boxMin.z);
    p.box = openvdb::CoordBBox(boxMin, boxMin.offsetBy(layout.dims.x - 1, layout.dims.y - 1, layout.dims.z - 1));
    const openvdb::math::Transform& transform = grid.transform();
    const openvdb::Vec3d spacing = transform.voxelSize();
    const openvdb::Vec3d first = transform.indexToWorld(p.box.min());
    p.spacing = {spacing.x(), spacing.y(), spacing.z()};
    // The box's corner is half a voxel below the first voxel's centre (cell-centred, vri's default).
    p.origin = glm::dvec3(first.x(), first.y(), first.z()) - (layout.indexAtVoxelCentres ? 0.5 : 0.0) * p.spacing;
    return p;
}

// Calls f(GridT*) with the grid's scalar type (isScalarGrid).
template <class F>
decltype(auto) dispatchGridType(const openvdb::GridBase& grid, const F& f) {
    if (grid.isType<openvdb::Int32Grid>()) return f(static_cast<openvdb::Int32Grid*>(nullptr));
    if (grid.isType<openvdb::Int64Grid>()) return f(static_cast<openvdb::Int64Grid*>(nullptr));
    if (grid.isType<openvdb::DoubleGrid>()) return f(static_cast<openvdb::DoubleGrid*>(nullptr));
    return f(static_cast<openvdb::FloatGrid*>(nullptr));
}

Volume toVolume(const fs::path& path, const openvdb::GridBase& grid, const GridPlacement& p) {
    const detail::VdbVolumeLayout& layout = p.layout;
    if (const auto refusal = denseSizeRefusal(path, p.source, layout.dims, layout.type)) throw Error(*refusal);
    Volume volume(layout.dims, layout.type);
    volume.spacing = p.spacing;
    volume.origin = p.origin;
    volume.range = layout.range;
    // vdbVolumeLayout has checked that the grid's value type can hold the layout's voxel type; the
    // values themselves are checked on the way (requireRepresentable).
    dispatchGridType(grid, [&]<class GridT>(GridT*) {
        dispatchVoxelType(layout.type, [&](auto t) { copyToVolume<decltype(t), GridT>(path, grid, p.box, volume); });
    });
    return volume;
}

// The sparse volume of the grid's leaves, straight from the tree: a brick may differ from the background
// only where a leaf node or a tile of another value overlaps its block (the brick and its apron), and only
// those bricks are read, voxel by voxel as copyToDense reads them (the tree's value, active or not, cast to T).
template <class T, class GridT>
SparseVolume toSparse(const fs::path& path, const GridT& grid, const GridPlacement& p) {
    if constexpr (!std::is_same_v<T, typename GridT::ValueType>) requireRepresentable<T>(path, grid);
    const glm::ivec3 dims = p.layout.dims;
    const glm::ivec3 bricks = SparseVolume::bricksOf(dims);
    const std::string sparse = boxDescription(path, p.source, dims, p.layout.type) + " kept sparse";
    if (const auto refusal = sizeRefusal(
            path, sparse + ", its brick table",
            {std::uint64_t(bricks.x), std::uint64_t(bricks.y), std::uint64_t(bricks.z), sizeof(std::uint32_t)}))
        throw Error(*refusal);
    const T background = static_cast<T>(grid.background());
    std::vector<std::uint8_t> candidates(static_cast<std::size_t>(bricks.x) * bricks.y * bricks.z, 0);
    const openvdb::Coord boxMin = p.box.min();
    // The bricks whose blocks [8b, 8b + 8] meet the index box [lo, hi] (inside the volume's box).
    const auto mark = [&](openvdb::CoordBBox region) {
        region.intersect(p.box);
        if (region.empty()) return;
        glm::ivec3 first, last;
        for (int a = 0; a < 3; ++a) {
            const int lo = region.min()[a] - boxMin[a], hi = region.max()[a] - boxMin[a];
            first[a] = lo > 0 ? (lo - 1) >> SparseVolume::kBrickShift : 0;
            last[a] = hi >> SparseVolume::kBrickShift;
        }
        for (int z = first.z; z <= last.z; ++z)
            for (int y = first.y; y <= last.y; ++y)
                for (int x = first.x; x <= last.x; ++x)
                    candidates[(static_cast<std::size_t>(z) * bricks.y + y) * bricks.x + x] = 1;
    };
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) mark(leaf->getNodeBoundingBox());
    typename GridT::TreeType::ValueAllCIter tile = grid.tree().cbeginValueAll();
    tile.setMaxDepth(GridT::TreeType::ValueAllCIter::LEAF_DEPTH - 1);  // tiles of the internal nodes and root
    for (; tile; ++tile) {
        const T value = static_cast<T>(*tile);
        if (std::memcmp(&value, &background, sizeof(T)) == 0) continue;
        openvdb::CoordBBox region;
        tile.getBoundingBox(region);
        mark(region);
    }
    // A tile stands for up to 4096^3 voxels in a few bytes of the file: the bricks that tiles and leaves
    // fill, each read voxel by voxel and then stored, are counted and checked before any is read.
    const auto filled = static_cast<std::uint64_t>(std::count(candidates.begin(), candidates.end(), 1));
    if (const auto refusal =
            sizeRefusal(path, sparse + ", the " + std::to_string(filled) + " bricks that its tiles and leaves fill",
                        {filled, SparseVolume::kBlockVoxels, sizeof(T)}))
        throw Error(*refusal);
    SparseVolume volume = SparseVolume::fromVoxels<T>(dims, background, candidates, [&] {
        return [accessor = grid.getConstAccessor(), boxMin](int x, int y, int z) mutable {
            return static_cast<T>(accessor.getValue(boxMin.offsetBy(x, y, z)));
        };
    });
    volume.spacing = p.spacing;
    volume.origin = p.origin;
    volume.range = p.layout.range;
    return volume;
}

bool isScalarGrid(const openvdb::GridBase& grid) {
    return grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>() ||
           grid.isType<openvdb::Int32Grid>() || grid.isType<openvdb::Int64Grid>();
}

std::string gridList(openvdb::io::File& file) {
    std::string names;
    const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    for (const openvdb::GridBase::Ptr& grid : *grids) names += (names.empty() ? "" : ", ") + gridDescription(*grid);
    return names.empty() ? "none" : names;
}

openvdb::GridBase::Ptr readScalarGrid(const fs::path& path, const std::optional<std::string>& gridName) {
    openvdb::io::File file(path.string());
    file.open(/*delayLoad=*/false);
    openvdb::GridBase::Ptr grid;
    if (gridName) {
        if (!file.hasGrid(*gridName))
            throw Error(path.string() + ": no grid named '" + *gridName + "' (grids: " + gridList(file) + ")");
        grid = file.readGrid(*gridName);
        if (!isScalarGrid(*grid))
            throw Error(path.string() + ": " + gridDescription(*grid) + " is not a float, double, int32 or int64 grid");
    } else {
        const openvdb::GridPtrVecPtr candidates = file.readAllGridMetadata();
        for (const openvdb::GridBase::Ptr& candidate : *candidates)
            if (isScalarGrid(*candidate)) {
                grid = file.readGrid(candidate->getName());
                break;
            }
        if (!grid)
            throw Error(path.string() + ": no float, double, int32 or int64 grid (grids: " + gridList(file) + ")");
    }
    file.close();
    return grid;
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

// The grid as a volume, dense or sparse; OpenVDB's exceptions become vri::Error naming the file.
LoadedVolume readGrid(const fs::path& path, const std::optional<std::string>& gridName, VolumeStorage storage) {
    try {
        const openvdb::GridBase::Ptr grid = readScalarGrid(path, gridName);
        const GridPlacement p = placement(path, *grid);
        const bool sparse = storage == VolumeStorage::Sparse ||
                            (storage == VolumeStorage::Auto &&
                             denseSizeRefusal(path, p.source, p.layout.dims, p.layout.type).has_value());
        if (!sparse) return {std::make_shared<Volume>(toVolume(path, *grid, p)), nullptr};
        return {nullptr, dispatchGridType(*grid, [&]<class GridT>(GridT*) {
                    return dispatchVoxelType(p.layout.type, [&](auto t) {
                        return std::make_shared<SparseVolume>(
                            toSparse<decltype(t)>(path, static_cast<const GridT&>(*grid), p));
                    });
                })};
    } catch (const openvdb::Exception& e) {
        throw Error(path.string() + ": " + e.what());
    }
}

// The grid as a volume (vdb_module.h's VdbModule::read), dense or sparse as `storage` asks.
std::string readGridFile(const fs::path& path, const std::optional<std::string>& gridName, VolumeStorage storage,
                         LoadedVolume& volume) {
    return detail::caughtMessage("OpenVDB", [&] {
        initializeOpenVdb();
        volume = detail::namingFileIfTooLarge(path, [&] { return readGrid(path, gridName, storage); });
    });
}

// The volume as a .vdb file's bytes (VdbModule::encode).
std::string encodeGridFile(const fs::path& path, const Volume& volume, std::string& bytes) {
    return detail::caughtMessage("OpenVDB", [&] {
        initializeOpenVdb();
        std::ostringstream encoded;
        try {
            SeekableArchive().writeTo(encoded, {toGrid(volume)});
        } catch (const openvdb::Exception& e) {
            throw Error(path.string() + ": " + e.what());
        } catch (const std::bad_alloc&) {
            throw OutOfMemory(path.string() + ": out of memory while encoding the grid");
        }
        if (!encoded) throw Error(path.string() + ": cannot encode the grid");
        bytes = std::move(encoded).str();
    });
}

}  // namespace

}  // namespace vri

// libvri-vdb.so's one exported symbol: the table of its functions.
extern "C" __attribute__((visibility("default"))) const vri::detail::VdbModule* vri_vdb_module_1() {
    static const vri::detail::VdbModule module{vri::readGridFile, vri::encodeGridFile};
    return &module;
}
