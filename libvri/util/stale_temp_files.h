#pragma once
// Temporary files that a killed process left behind. writeAtomically names its temporary file
// ".NAME.tmp.PID" + extension beside the target; a process killed by a signal (kill -9, a power cut)
// leaves it there. Its pid tells whether the writer may still be at work.
#include <filesystem>
#include <vector>

namespace vri {

// Removes the files directly in `folder` named ".NAME.tmp.PID[.anything]" whose process PID is gone
// (no such process: kill(PID, 0) fails with ESRCH); a live process's file, and every other entry, is
// left alone, as is anything that is not a regular file. Returns the files removed.
std::vector<std::filesystem::path> removeStaleTempFiles(const std::filesystem::path& folder);

}  // namespace vri
