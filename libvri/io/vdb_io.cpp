// readVdb and writeVdb (volume_io.h) through vri's OpenVDB module (vdb_module.h).
#include <utility>

#include "libvri/io/io_module.h"
#include "libvri/io/vdb_file_extent.h"
#include "libvri/io/vdb_module.h"
#include "libvri/io/volume_formats.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace detail {

const VdbModule& vdbModule(const fs::path& path, std::string_view doing) {
    return moduleTable<VdbModule>(kVdbModuleFile, kVdbModuleEntry, path, doing, ".vdb files need vri's OpenVDB module");
}

}  // namespace detail

Volume readVdb(const fs::path& path, const std::optional<std::string>& gridName) {
    LoadedVolume loaded = readVdb(path, gridName, VolumeStorage::Dense);
    return std::move(*loaded.dense);
}

LoadedVolume readVdb(const fs::path& path, const std::optional<std::string>& gridName, VolumeStorage storage) {
    detail::requireRegularFile(path);
    detail::requireWholeVdbFile(path);
    LoadedVolume loaded;
    detail::requireModuleSuccess(detail::vdbModule(path, "read volume").read(path, gridName, storage, loaded));
    return loaded;
}

void writeVdb(const fs::path& path, const Volume& volume) {
    if (volume.bytes.size() != volume.byteCount() || volume.voxelCount() == 0)
        throw Error(path.string() + ": volume holds " + std::to_string(volume.bytes.size()) +
                    " bytes, which does not match its dims");
    std::string bytes;
    detail::requireModuleSuccess(detail::vdbModule(path, "write volume").encode(path, volume, bytes));
    writeTextFile(path, bytes);
}

}  // namespace vri
