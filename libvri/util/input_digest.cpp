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

InputDigests InputDigests::fromEnvironment() {
    InputDigests digests;
    const char* named = std::getenv(kInputDigestsVariable);
    if (!named || !*named) return digests;
    digests.record_ = named;
    const std::string where = std::string(kInputDigestsVariable) + " " + digests.record_.string();
    nlohmann::json j;
    try {
        j = readJsonFile(digests.record_);
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    }
    try {
        for (const nlohmann::json& f : j.at("files"))
            digests.entries_.push_back({f.at("path").get<std::string>(),
                                        {f.at("size").get<std::uintmax_t>(), f.at("mtime_ns").get<long long>()},
                                        f.at("sha512").get<std::string>()});
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": not a record of digests (" + e.what() + ")");
    }
    return digests;
}

InputDigest InputDigests::of(const fs::path& path) const {
    if (const std::optional<FileStamp> stamp = entries_.empty() ? std::nullopt : fileStamp(path)) {
        const std::string absolute = fs::absolute(path).lexically_normal().string();
        for (const Entry& e : entries_)
            if (e.path == absolute && e.stamp == *stamp) return {e.sha512, record_};
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
