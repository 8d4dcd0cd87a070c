#include "libvri/io/plot_data_files.h"

#include <algorithm>

#include "libvri/io/yaml_util.h"

namespace vri {

namespace fs = std::filesystem;

fs::path plotDataPath(const std::string& file, const fs::path& dataDir) {
    return (fs::path(file).is_absolute() ? fs::path(file) : dataDir / file).lexically_normal();
}

std::vector<fs::path> plotDataFiles(const fs::path& spec, const fs::path& dataDir) {
    const YAML::Node root = yaml::load(spec);
    std::vector<fs::path> files;
    const auto addSeries = [&](const YAML::Node& panel) {
        const YAML::Node series = panel.IsMap() ? panel["series"] : YAML::Node();
        if (!series || !series.IsSequence()) return;
        for (const YAML::Node& s : series) {
            const YAML::Node file = s.IsMap() ? s["file"] : YAML::Node();
            if (!file || !file.IsScalar()) continue;
            const fs::path path = plotDataPath(file.as<std::string>(), dataDir);
            if (std::find(files.begin(), files.end(), path) == files.end()) files.push_back(path);
        }
    };
    if (!root.IsMap()) return files;
    if (const YAML::Node panels = root["panels"]; panels && panels.IsSequence())
        for (const YAML::Node& panel : panels) addSeries(panel);
    else
        addSeries(root);
    return files;
}

}  // namespace vri
