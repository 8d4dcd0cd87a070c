// A file's digest from its launcher's record while the file keeps its size and modification time, computed
// otherwise (util/input_digest.h).
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "libvri/util/error.h"
#include "libvri/util/input_digest.h"
#include "libvri/util/sha512.h"

namespace fs = std::filesystem;
using namespace vri;

namespace {

// VRI_INPUT_DIGESTS set for one scope, as it was afterwards.
struct RecordNamed {
    explicit RecordNamed(const fs::path& record) {
        if (const char* old = std::getenv(kInputDigestsVariable)) previous = old, had = true;
        ::setenv(kInputDigestsVariable, record.c_str(), 1);
    }
    ~RecordNamed() { had ? ::setenv(kInputDigestsVariable, previous.c_str(), 1) : ::unsetenv(kInputDigestsVariable); }
    std::string previous;
    bool had = false;
};

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

}  // namespace

TEST_CASE("input digests: taken from the record while size and time hold, computed otherwise") {
    const fs::path dir = fs::temp_directory_path() / ("vri-input-digest-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path file = dir / "volume.raw", record = dir / "record.json";
    write(file, "12345678");
    const std::string real = sha512File(file);
    // A record that says something else for the file: what comes back is the record's, so nothing was read. A
    // file written since it was hashed (another stamp) is left out of the record.
    write(dir / "stale.raw", "abc");
    const FileStamp stale{3, fileStamp(dir / "stale.raw")->mtimeNs - 1};
    writeDigestRecord(record, {{file, "recorded", *fileStamp(file)}, {dir / "stale.raw", "stale", stale}});
    {
        const RecordNamed named(record);
        const InputDigest d = InputDigests::fromEnvironment().of(file);
        CHECK(d.sha512 == "recorded");
        CHECK(d.record == record);
        // Another file of the same size is not the recorded one.
        write(dir / "other.raw", "87654321");
        CHECK(InputDigests::fromEnvironment().of(dir / "other.raw").sha512 == sha512File(dir / "other.raw"));
        // The same path, relative: the record lists absolute paths.
        const fs::path here = fs::current_path();
        fs::current_path(dir);
        CHECK(InputDigests::fromEnvironment().of("volume.raw").sha512 == "recorded");
        fs::current_path(here);
        // Written again (same size, later time): computed.
        fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(1));
        const InputDigest again = InputDigests::fromEnvironment().of(file);
        CHECK(again.sha512 == real);
        CHECK(again.record.empty());
    }
    {
        const RecordNamed named(record);
        CHECK(InputDigests::fromEnvironment().of(dir / "stale.raw").sha512 == sha512File(dir / "stale.raw"));
    }
    CHECK(InputDigests::fromEnvironment().of(file).sha512 == real);  // no record named
    // A link in the record's place is replaced, its target untouched.
    write(dir / "target.txt", "kept");
    fs::remove(record);
    fs::create_symlink(dir / "target.txt", record);
    writeDigestRecord(record, {});
    CHECK_FALSE(fs::is_symlink(record));
    std::ifstream target(dir / "target.txt");
    std::string kept;
    target >> kept;
    CHECK(kept == "kept");
    write(record, "{\"files\": [{\"path\": 3}]}");
    {
        const RecordNamed named(record);
        const std::string expected = "VRI_INPUT_DIGESTS " + record.string() + ": not a record of digests";
        CHECK_THROWS_WITH_AS(InputDigests::fromEnvironment().of(file), doctest::Contains(expected.c_str()), Error);
    }
    {
        const RecordNamed named(dir / "no-such-record.json");
        const std::string expected = "VRI_INPUT_DIGESTS " + (dir / "no-such-record.json").string() + ": ";
        CHECK_THROWS_WITH_AS(InputDigests::fromEnvironment().of(file), doctest::Contains(expected.c_str()), Error);
    }
    fs::remove_all(dir);
}
