#pragma once
// Where a volume named on a command line, in an experiment file or from Python is found: the datasets live
// outside the repository, in a data directory ($VRI_DATA_DIR), so a bare file name means the file there
// unless one of that name is at hand.
#include <filesystem>
#include <optional>

namespace vri {

// $VRI_DATA_DIR when set and not empty, else ../shared/data/volumes relative to the current directory.
std::filesystem::path defaultDataDir();

// `path` when it names a regular file (a relative one taken from `base`), else, for a relative path, that path
// in defaultDataDir(); nullopt when neither exists.
std::optional<std::filesystem::path> findVolume(const std::filesystem::path& path, const std::filesystem::path& base);

}  // namespace vri
