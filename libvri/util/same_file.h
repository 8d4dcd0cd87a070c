#pragma once
// Whether two paths name one file, so that a tool can refuse an output that would replace one of its
// own inputs before it reads or writes anything.
#include <filesystem>

namespace vri {

// True when both paths name existing regular files with the same device and inode: the same file
// through any spelling, symbolic link (followed) or hard link. A path that does not exist names no
// file yet, so it is the same as nothing; devices and FIFOs (/dev/stdin and /dev/stdout may be one
// terminal) never count, since writing one does not replace what another reads.
bool sameExistingFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace vri
