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

std::optional<FileStamp> fileStamp(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return std::nullopt;
    FileStamp stamp;
    stamp.size = fs::file_size(path, ec);
    if (ec) return std::nullopt;
    const auto time = fs::last_write_time(path, ec);
    if (ec) return std::nullopt;
    stamp.mtimeNs =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::file_clock::to_sys(time).time_since_epoch())
            .count();
    return stamp;
}

InputDigest inputDigest(const fs::path& path) {
    const char* named = std::getenv(kInputDigestsVariable);
    if (const std::optional<FileStamp> stamp = named && *named ? fileStamp(path) : std::nullopt) {
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
                if (f.at("path").get<std::string>() == absolute && f.at("size").get<std::uintmax_t>() == stamp->size &&
                    f.at("mtime_ns").get<long long>() == stamp->mtimeNs)
                    return {f.at("sha512").get<std::string>(), record};
        } catch (const nlohmann::json::exception& e) {
            throw Error(where + ": not a record of digests (" + e.what() + ")");
        }
    }
    return {sha512File(path), {}};
}

void writeDigestRecord(const fs::path& record, const std::vector<StampedDigest>& digests) {
    nlohmann::json files = nlohmann::json::array();
    for (const StampedDigest& d : digests)
        if (fileStamp(d.path) == d.stamp)
            files.push_back({{"path", fs::absolute(d.path).lexically_normal().string()},
                             {"size", d.stamp.size},
                             {"mtime_ns", d.stamp.mtimeNs},
                             {"sha512", d.sha512}});
    std::error_code ec;
    if (fs::is_symlink(record, ec)) fs::remove(record);
    writeTextFile(record, nlohmann::json{{"files", files}}.dump(2) + "\n");
}

}  // namespace vri
