#include "libvri/core/voxel_loads.h"

#include <cstdlib>
#include <string>

#include "libvri/core/engine_environment.h"
#include "libvri/util/error.h"
#include "libvri/util/printable.h"

namespace vri {

VoxelLoads voxelLoads() {
    const char* value = std::getenv(kVoxelLoadsVariable);
    if (value != nullptr && *value != '\0') {
        const std::string v = value;
        for (VoxelLoads loads : {VoxelLoads::Gather, VoxelLoads::Scalar})
            if (v == voxelLoadsName(loads)) return loads;
        throw Error(std::string(kVoxelLoadsVariable) + ": expected gather or scalar, got '" + printable(v) + "'");
    }
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_is("amd") ? VoxelLoads::Scalar : VoxelLoads::Gather;
#else
    return VoxelLoads::Gather;
#endif
}

const char* voxelLoadsName(VoxelLoads loads) { return loads == VoxelLoads::Scalar ? "scalar" : "gather"; }

}  // namespace vri
