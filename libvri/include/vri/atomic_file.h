#pragma once
// Outputs are written to a temporary file beside the target and renamed into place, so an
// interrupted run never leaves a truncated file that a later run would trust.
#include <filesystem>
#include <functional>
#include <string>

namespace vri {

// Calls write(tmp) with a temporary path in the target's directory that keeps the target's
// extension (image libraries pick the format from it), then renames tmp to `path`.
// On any exception the temporary file is removed and `path` is left as it was.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes `text` to `path` atomically; "-" writes to stdout.
void writeTextFile(const std::filesystem::path& path, const std::string& text);

}  // namespace vri
