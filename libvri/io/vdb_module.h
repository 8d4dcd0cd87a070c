#pragma once
// OpenVDB as a module vri loads when a .vdb file is read or written (libvri-vdb.so, libvri/io/vdb/;
// io_module.h): linked into every tool, its 61,000 symbol relocations cost each process some 65 ms before
// main(), most of a small tool's run. Private to io/; includes no OpenVDB header.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "libvri/io/volume_io.h"

namespace vri::detail {

// The module's functions; each returns "" when it succeeded, else its one-line message naming the file.
struct VdbModule {
    // readVdb's work after its checks of the file (volume_io.h): the grid as a volume, dense or sparse.
    std::string (*read)(const std::filesystem::path& path, const std::optional<std::string>& gridName,
                        VolumeStorage storage, LoadedVolume& volume);
    // The volume as the bytes of a .vdb file, for writeVdb to write through its checked writes.
    std::string (*encode)(const std::filesystem::path& path, const Volume& volume, std::string& bytes);
};

inline constexpr const char* kVdbModuleEntry = "vri_vdb_module_1";
inline constexpr const char* kVdbModuleFile = "libvri-vdb.so";

// The module, loaded on first use (once per process). Throws vri::Error "PATH: cannot <doing>: ..." naming
// where the module was looked for when it cannot be loaded.
const VdbModule& vdbModule(const std::filesystem::path& path, std::string_view doing);

}  // namespace vri::detail
