#pragma once
// The environment variables that choose which code a render runs, not what it computes: VRI_SIMD_TARGET
// (the Highway target of the packets and the Gauss batches, simd_target.h) and VRI_VOXEL_LOADS (how the
// AVX2 packets read voxels, voxel_loads.h). Every image is the same bit for bit; times and the stats that
// name the code differ, so the provenance records them and the step cache counts a run with them as
// another run.
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace vri {

inline constexpr const char* kSimdTargetVariable = "VRI_SIMD_TARGET";
inline constexpr const char* kVoxelLoadsVariable = "VRI_VOXEL_LOADS";
inline constexpr std::array<const char*, 2> kEngineVariables = {kSimdTargetVariable, kVoxelLoadsVariable};

// The ones set to something (an empty value counts as unset, as their readers take it): name and value,
// in kEngineVariables' order; a SIMD target as simdTargetNamed spells it (avx2 is AVX2).
std::vector<std::pair<std::string, std::string>> engineEnvironment();

// Throws vri::Error naming the variable when either holds a value its reader refuses, so that a command
// refuses it before any work, whether or not its render would have read it.
void checkEngineEnvironment();

}  // namespace vri
