// vri-data: makes the catalog's datasets available (`make data`): checks each one in the data
// directory against its SHA-512 and downloads what is missing.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/experiment/datasets.h"

namespace {

constexpr const char* kTool = "vri-data";

int run(int argc, char** argv) {
    std::string catalogPath = "experiments/datasets.yaml";
    std::string dataDir;
    std::vector<std::string> only;
    bool noDownload = false;
    CLI::App app{"Checks the datasets of the catalog in the data directory (size and SHA-512) and downloads the "
                 "missing ones from their published URLs. One line per dataset: verified, ok, downloaded, "
                 "MISSING or MISMATCH.",
                 kTool};
    app.add_option("--catalog", catalogPath, "dataset catalog YAML")->capture_default_str();
    app.add_option("--data-dir", dataDir, "where the datasets are (default: $VRI_DATA_DIR, else "
                                          "../shared/data/volumes); downloads go there too");
    vri::addListOption(app, "--only", only, "check only these datasets, comma separated");
    app.add_flag("--no-download", noDownload, "report missing datasets instead of downloading them");
    app.footer(
        "Exit status: 0 when every dataset is verified, ok or downloaded; 1 when any is MISSING or MISMATCH.\n"
        "'ok' means present with the right size but not held to a digest: none is recorded, or the dataset is\n"
        "reconstructed and its recorded digest identifies our reconstruction, not a published file.\n"
        "\n"
        "Examples:\n"
        "  VRI_DATA_DIR=../shared/data/volumes vri-data\n"
        "      check every dataset; fetch the missing ones (curl or wget)\n"
        "  vri-data --data-dir data --only bonsai,blunt_fin --no-download\n"
        "      check two datasets in ./data, download nothing");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    const std::vector<vri::DatasetInfo> catalog = vri::loadDatasetCatalog(catalogPath);
    for (const std::string& name : only) vri::findDataset(catalog, name, "--only");
    const std::filesystem::path dir = dataDir.empty() ? vri::defaultDataDir() : std::filesystem::path(dataDir);
    std::cout << "data directory: " << dir.string() << '\n';
    int failures = 0;
    for (const vri::DatasetInfo& info : catalog) {
        if (!only.empty() && std::find(only.begin(), only.end(), info.name) == only.end()) continue;
        const vri::DatasetCheck check = vri::checkDataset(info, dir, !noDownload);
        failures += check.state == vri::DatasetState::Missing || check.state == vri::DatasetState::Mismatch;
        std::cout << std::left << std::setw(11) << vri::datasetStateName(check.state) << std::setw(15) << info.name
                  << check.detail << (info.status == "exact" ? "" : " [" + info.status + "]") << std::endl;
    }
    if (failures > 0)
        throw vri::Error(std::to_string(failures) + " dataset" + (failures == 1 ? " is" : "s are") +
                         " missing or mismatched in " + dir.string() +
                         (noDownload ? " (without --no-download they are fetched)" : ""));
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
