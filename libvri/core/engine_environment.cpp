#include "libvri/core/engine_environment.h"

#include <cstdlib>

#include "libvri/core/simd_target.h"
#include "libvri/core/voxel_loads.h"

namespace vri {

std::vector<std::pair<std::string, std::string>> engineEnvironment() {
    std::vector<std::pair<std::string, std::string>> set;
    for (const char* name : kEngineVariables)
        if (const char* value = std::getenv(name); value != nullptr && *value != '\0') set.emplace_back(name, value);
    return set;
}

void checkEngineEnvironment() {
    simdTargetFromEnvironment();
    voxelLoads();
}

}  // namespace vri
