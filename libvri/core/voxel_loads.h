#pragma once
// How the packet engine's AVX2 target reads the voxels of its lanes' trilinear stencils (8-bit volumes)
// and, with empty-space skipping, their bricks' distances to visible space (any volume; simd_march.cpp):
// with gather instructions, or lane by lane with scalar loads. The two read the same bytes, so the image is the same bit for bit; which is
// faster depends on the CPU. AMD's AVX2 gathers are microcoded (Zen 3: 39 micro-ops, one per 8 cycles,
// by uops.info's measurements), and scalar loads made the AVX2 packets 7 to 12 % faster on an AMD EPYC
// (Zen 4) on Bonsai and Engine (the stencils at h = 0.1, the distances 8 % more at h = 0.5). Intel's
// gathers are a few micro-ops, where the scalar loads' inserts would queue on one shuffle port: Intel
// keeps the gathers (not measured here). VRI_VOXEL_LOADS=gather or scalar overrides the vendor's
// choice for every render of a process (the tests run both).
namespace vri {

enum class VoxelLoads { Gather, Scalar };

// VRI_VOXEL_LOADS's choice when it is set and not empty, else Scalar on an AMD CPU and Gather on any
// other; throws vri::Error naming the variable when it holds anything but "gather" or "scalar".
VoxelLoads voxelLoads();

// "gather" or "scalar", as VRI_VOXEL_LOADS and the stats spell them.
const char* voxelLoadsName(VoxelLoads loads);

}  // namespace vri
