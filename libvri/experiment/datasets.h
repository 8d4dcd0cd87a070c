#pragma once
// The catalog of volume datasets the experiments use (experiments/datasets.yaml): where each file
// is published, how its voxels are laid out, the SHA-512 it must have, and how exact our copy is.
// The files themselves are not in the repository; they live in a data directory ($VRI_DATA_DIR).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "libvri/core/voxel_type.h"
#include "libvri/io/volume_io.h"
#include "libvri/io/volume_lookup.h"  // defaultDataDir(), where the datasets are

namespace vri {

struct DatasetInfo {
    std::string name;    // what experiments call it: "bonsai"
    std::string file;    // the raw voxels, relative to the data directory
    std::string sha512;  // of `file`; empty when no digest is recorded
    std::string url;     // where `file` is published
    std::string status;  // "exact", "reconstructed" or "stand-in" (see kDatasetStatuses)
    std::string note;    // how exact the copy is, in a sentence or two
    glm::ivec3 dims{0, 0, 0};
    VoxelType type = VoxelType::UInt8;
    ByteOrder order = ByteOrder::Little;
    glm::dvec3 spacing{1.0, 1.0, 1.0};
    std::string header;     // a header file beside `file` (e.g. Inviwo boron.dat), or empty
    std::string headerUrl;  // where `header` is published, or empty
};

// Exact: byte-identical to the published file. Reconstructed: rebuilt from other published data,
// `note` says how close it is; its digest identifies our reconstruction, not a published file.
// Stand-in: a different dataset used in place of one the papers name.
inline constexpr const char* kDatasetStatuses[] = {"exact", "reconstructed", "stand-in"};

// True when `yaml` is a dataset catalog (a map with `datasets:` and no experiment `name:`), as
// experiments/datasets.yaml beside the experiments: what `vri-run experiments/*.yaml` skips. A file that is
// not YAML is not one (reading it as an experiment then says what is wrong).
bool isDatasetCatalog(const std::filesystem::path& yaml);

// Reads and validates the catalog; any error is a vri::Error "file:line:col: what is wrong".
std::vector<DatasetInfo> loadDatasetCatalog(const std::filesystem::path& yaml);
std::vector<DatasetInfo> parseDatasetCatalog(const std::string& yamlText, const std::string& source);

// The dataset called `name`; throws "<where>: unknown dataset 'x' (known: a, b, ...)".
const DatasetInfo& findDataset(const std::vector<DatasetInfo>& catalog, const std::string& name,
                               const std::string& where);

// The file to open: the header if any (readVolume picks the format from it), else the raw file.
std::filesystem::path datasetPath(const DatasetInfo& info, const std::filesystem::path& dataDir);
// The raw file's layout, for readRaw or vri-render's --dims/--type/--byte-order/--spacing.
RawLayout rawLayout(const DatasetInfo& info);

// True when the raw file (and header, if any) exists, has the size its layout says and, when a
// digest is recorded, that SHA-512. Otherwise false, with the reason in *why (if not null).
bool verifyDataset(const DatasetInfo& info, const std::filesystem::path& dataDir, std::string* why);

// What `make data` found for one dataset.
enum class DatasetState {
    Verified,    // present, and its SHA-512 is the recorded one
    Ok,          // present with the right size; the digest is not checked (none recorded, or a
                 // reconstructed dataset whose recorded digest is ours, not a published one)
    Downloaded,  // was missing, fetched from its url, and checked as above
    Missing,     // absent (and not downloaded, or the download failed)
    Mismatch     // present or downloaded, but with the wrong size or SHA-512
};
std::string_view datasetStateName(DatasetState state);  // "verified", ..., "MISSING", "MISMATCH"

struct DatasetCheck {
    DatasetState state = DatasetState::Missing;
    std::string detail;  // one line: what was checked, or what is wrong and where
};

// Checks one dataset in dataDir. When it is absent and `download` is set, fetches `url` (and
// `headerUrl`) with curl or wget into dataDir (created if needed): each file goes to a temporary
// name and is renamed into place only once its size and digest are right, so a broken download
// never looks like data. A reconstructed dataset whose digest differs is reported Ok, not
// Mismatch: no published digest exists to hold it to.
DatasetCheck checkDataset(const DatasetInfo& info, const std::filesystem::path& dataDir, bool download);

}  // namespace vri
