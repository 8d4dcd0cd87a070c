#pragma once
// A folder vri keeps its own files in and deletes from (an experiment's .steps/, its Slurm job files):
// never reached through a symbolic link, which would take those writes, and a recursive delete, out of the
// results tree into whatever the link names (a results folder copied from elsewhere may hold one).
#include <filesystem>

namespace vri {

// Nothing at `folder`, or a real folder: fine (vri creates it when it needs it). A symbolic link, or
// anything else: vri::Error "FOLDER: is a symbolic link (to TARGET); vri-run keeps its own files there and
// will not write or delete through a link: remove it" (or "... is not a folder").
void requireOwnFolder(const std::filesystem::path& folder);

}  // namespace vri
