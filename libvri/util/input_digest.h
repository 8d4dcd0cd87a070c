#pragma once
// A file's SHA-512 for a record's provenance, taken from a record of digests that the process's launcher made
// (vri-run, for the steps it runs: VRI_INPUT_DIGESTS names the record) where the file's size and modification
// time are still those recorded, else computed. A brick job then records its volume's digest without reading
// the whole file, of which it reads only its brick. The file is trusted to have kept its contents while its
// size and nanosecond modification time stayed: the test make and rsync use, not a proof.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vri {

struct InputDigest {
    std::string sha512;
    std::filesystem::path record;  // the record it came from; empty when computed here
};

// Throws vri::Error naming VRI_INPUT_DIGESTS when the record it names cannot be read or is malformed.
InputDigest inputDigest(const std::filesystem::path& path);

// Writes the record for `digests` (each file's digest as computed now; files that are gone are left out):
// {"files": [{"path", "size", "mtime_ns", "sha512"}, ...]}, paths absolute.
void writeDigestRecord(const std::filesystem::path& record,
                       const std::vector<std::pair<std::filesystem::path, std::string>>& digests);

inline constexpr const char* kInputDigestsVariable = "VRI_INPUT_DIGESTS";

}  // namespace vri
