#include "libvri/core/engine_environment.h"

#include <cstdlib>

#include "libvri/core/simd_target.h"
#include "libvri/core/voxel_loads.h"

namespace vri {

std::vector<std::pair<std::string, std::string>> engineEnvironment() {
    std::vector<std::pair<std::string, std::string>> set;
    for (const char* name : kEngineVariables)
        if (const char* value = std::getenv(name); value != nullptr && *value != '\0') {
            // A target's name in any case is the same target: as its reader spells it, where it names one.
            const std::string target = name == kSimdTargetVariable ? simdTargetNamed(value) : std::string();
            set.emplace_back(name, target.empty() ? std::string(value) : target);
        }
    return set;
}

void checkEngineEnvironment() {
    simdTargetFromEnvironment();
    voxelLoads();
}

}  // namespace vri
