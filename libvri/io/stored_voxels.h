#pragma once
// Private to the volume readers: the voxel types files store, and how they become a vri volume. uint8,
// uint16 and float32 are kept as they are. Every other type becomes float32, by one rule:
//   - integers (int8, int16, int32, uint32) are converted to the nearest float, exact up to 2^24 in
//     magnitude (every int8 and int16 value); unless the file states a range, the normalisation range is
//     the stored type's full range, as it would be for a uint8 or uint16 volume;
//   - float64 is rounded to the nearest float32; a value beyond float32's range is refused.
#include <cstddef>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "libvri/core/volume.h"
#include "libvri/core/voxel_type.h"

namespace vri::detail {

enum class StoredType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::size_t storedSize(StoredType type);
std::string_view storedTypeName(StoredType type);  // "int8", "uint8", ..., "float64"
StoredType storedTypeOf(VoxelType type);
// The voxel type a volume of stored `type` is kept in.
VoxelType volumeTypeFor(StoredType type);
// True when that voxel type is `type` itself (uint8, uint16, float32): the voxels are kept as stored, so that a
// box of them can be read by offset, not converted from the whole file's.
bool keptAsStored(StoredType type);

// The volume of `dims` whose voxels are `bytes` (x fastest, each in `order`), converted by the rule above.
// The caller has checked that bytes.size() is the voxel count times storedSize(type); `source` names the
// file in messages.
Volume decodeVoxels(const std::string& source, glm::ivec3 dims, StoredType type, ByteOrder order,
                    std::string_view bytes);

}  // namespace vri::detail
