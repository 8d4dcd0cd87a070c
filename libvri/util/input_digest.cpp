#include "libvri/util/input_digest.h"

#include <chrono>
#include <cstdlib>
#include <system_error>

#include <nlohmann/json.hpp>

#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/json_file.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// Size and modification time in nanoseconds, or false when the file cannot be looked at.
bool stamp(const fs::path& path, std::uintmax_t& size, long long& mtime) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    size = fs::file_size(path, ec);
    if (ec) return false;
    const auto time = fs::last_write_time(path, ec);
    if (ec) return false;
    mtime =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::file_clock::to_sys(time).time_since_epoch())
            .count();  // since the Unix epoch
    return true;
}

}  // namespace

InputDigest inputDigest(const fs::path& path) {
    const char* named = std::getenv(kInputDigestsVariable);
    std::uintmax_t size = 0;
    long long mtime = 0;
    if (named && *named && stamp(path, size, mtime)) {
        const fs::path record = named;
        const std::string where = std::string(kInputDigestsVariable) + " " + record.string();
        nlohmann::json j;
        try {
            j = readJsonFile(record);
        } catch (const Error& e) {
            throw Error(where + ": " + e.what());
        }
        const std::string absolute = fs::absolute(path).lexically_normal().string();
        try {
            for (const nlohmann::json& f : j.at("files"))
                if (f.at("path").get<std::string>() == absolute && f.at("size").get<std::uintmax_t>() == size &&
                    f.at("mtime_ns").get<long long>() == mtime)
                    return {f.at("sha512").get<std::string>(), record};
        } catch (const nlohmann::json::exception& e) {
            throw Error(where + ": not a record of digests (" + e.what() + ")");
        }
    }
    return {sha512File(path), {}};
}

void writeDigestRecord(const fs::path& record, const std::vector<std::pair<fs::path, std::string>>& digests) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& [path, sha512] : digests) {
        std::uintmax_t size = 0;
        long long mtime = 0;
        if (stamp(path, size, mtime))
            files.push_back({{"path", fs::absolute(path).lexically_normal().string()},
                             {"size", size},
                             {"mtime_ns", mtime},
                             {"sha512", sha512}});
    }
    writeTextFile(record, nlohmann::json{{"files", files}}.dump(2) + "\n");
}

}  // namespace vri
