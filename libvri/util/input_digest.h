#pragma once
// A file's SHA-512 for a record's provenance, taken from a record of digests that the process's launcher made
// (vri-run, for the steps it runs: VRI_INPUT_DIGESTS names the record) where the file's size and modification
// time are still those recorded, else computed. A brick job then records its volume's digest without reading
// the whole file, of which it reads only its brick. The file is trusted to have kept its contents while its
// size and nanosecond modification time stayed: the test make and rsync use, not a proof.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vri {

struct InputDigest {
    std::string sha512;
    std::filesystem::path record;  // the record it came from; empty when computed here
};

// A file's size and modification time (ns since the Unix epoch, as fine as the file system keeps it).
struct FileStamp {
    std::uintmax_t size = 0;
    long long mtimeNs = 0;
    bool operator==(const FileStamp&) const = default;
};
std::optional<FileStamp> fileStamp(const std::filesystem::path& path);  // nullopt: not a regular file

// The record VRI_INPUT_DIGESTS names, read once, and the digests of files looked up in it.
class InputDigests {
public:
    // Reads the record VRI_INPUT_DIGESTS names (none when it is unset or empty); throws vri::Error naming it when
    // it cannot be read or is malformed.
    static InputDigests fromEnvironment();
    // The record's digest of `path` where its absolute path, size and modification time are the recorded ones,
    // else computed.
    InputDigest of(const std::filesystem::path& path) const;

private:
    struct Entry {
        std::string path;  // absolute
        FileStamp stamp;
        std::string sha512;
    };
    std::filesystem::path record_;
    std::vector<Entry> entries_;
};

// A file's digest with the stamp it had before it was hashed.
struct StampedDigest {
    std::filesystem::path path;
    std::string sha512;
    FileStamp stamp;
};
// Writes the record {"files": [{"path", "size", "mtime_ns", "sha512"}, ...]}, paths absolute, of the files whose
// stamp is still the one they were hashed with (one written since is left out, and then computed by whoever
// needs it); a link in the record's place is removed, never written through.
void writeDigestRecord(const std::filesystem::path& record, const std::vector<StampedDigest>& digests);

inline constexpr const char* kInputDigestsVariable = "VRI_INPUT_DIGESTS";

}  // namespace vri
