#pragma once
// Private to the .vdb reader: whether a .vdb file holds every byte its own header promises, checked
// before OpenVDB reads it. OpenVDB reads a file cut short past its end and reports whatever it then
// trips over (a failed decompression, a bad node, out of memory), not always the same from run to run;
// the grid descriptors of a seekable file (every one vri and OpenVDB write) say where each grid ends, so
// one walk over them names the cut instead. No OpenVDB header: this reads the bytes as the format lays
// them out (openvdb/io/Archive.cc, GridDescriptor.cc).
#include <filesystem>

namespace vri::detail {

// Throws vri::Error "<path>: cut short: ..." naming the byte where the header, a grid's descriptor or a
// grid ends beyond the file's end, or "<path>: not a VDB file (...)" when it does not start with OpenVDB's
// magic number. A file of an old format version (before 218) or without grid offsets is left to OpenVDB.
void requireWholeVdbFile(const std::filesystem::path& path);

}  // namespace vri::detail
