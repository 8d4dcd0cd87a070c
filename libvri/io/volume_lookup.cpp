#include "libvri/io/volume_lookup.h"

#include <cstdlib>

namespace vri {

namespace fs = std::filesystem;

fs::path defaultDataDir() {
    const char* fromEnvironment = std::getenv("VRI_DATA_DIR");
    if (fromEnvironment != nullptr && *fromEnvironment != '\0') return fromEnvironment;
    return fs::path("..") / "shared" / "data" / "volumes";
}

std::optional<fs::path> findVolume(const fs::path& path, const fs::path& base) {
    const fs::path beside = (base / path).lexically_normal();
    if (fs::is_regular_file(beside)) return fs::absolute(beside);
    const fs::path inData = (defaultDataDir() / path).lexically_normal();
    if (path.is_relative() && fs::is_regular_file(inData)) return fs::absolute(inData);
    return std::nullopt;
}

}  // namespace vri
