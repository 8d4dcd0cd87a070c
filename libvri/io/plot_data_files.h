#pragma once
// The data files a figure spec names (vri-plot's spec, libvri/report/plot.h): where vri-plot opens them,
// and the list of them, so that the step that draws the figure is keyed by every file it reads, wherever
// it lies (another experiment's results included), not only by those the experiment lists as `data`.
#include <filesystem>
#include <string>
#include <vector>

namespace vri {

// Where vri-plot opens a series' `file`: as it is when absolute, else from `dataDir`; lexically normal.
std::filesystem::path plotDataPath(const std::string& file, const std::filesystem::path& dataDir);

// Every series' `file` of the spec at `spec` (its top-level `series`, or each of its `panels`), at
// plotDataPath, in order and once each. Nothing else of the spec is checked here (vri-plot checks it
// when it draws); throws vri::Error "<spec>:line:col: ..." when the spec is not a YAML file.
std::vector<std::filesystem::path> plotDataFiles(const std::filesystem::path& spec,
                                                 const std::filesystem::path& dataDir);

}  // namespace vri
