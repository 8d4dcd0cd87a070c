// `make data`: checking each catalog dataset in the data directory and fetching what is missing.
#include <sys/wait.h>

#include <cstdlib>
#include <optional>
#include <system_error>

#include "vri/datasets.h"
#include "vri/provenance.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

bool commandExists(const std::string& name) {
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

// Downloads url to `target` through a temporary name beside it. Returns the reason on failure.
std::optional<std::string> fetchUrl(const std::string& url, const fs::path& target) {
    std::string command;
    // -f: an HTTP error is a failure, not a saved error page.
    if (commandExists("curl")) command = "curl -fsSL --retry 2 -o ";
    else if (commandExists("wget")) command = "wget -q -O ";
    else return "neither curl nor wget is installed";
    const fs::path partial = target.parent_path() / std::string(".").append(target.filename().string()).append(".download");
    const int status = std::system((command + shellQuote(partial.string()) + " " + shellQuote(url)).c_str());
    std::error_code ec;
    if (status != 0) {
        const int code = WIFEXITED(status) ? WEXITSTATUS(status) : status;
        fs::remove(partial, ec);
        return "download of " + url + " failed (" + command.substr(0, command.find(' ')) + " exit status " +
               std::to_string(code) + ")";
    }
    fs::rename(partial, target, ec);
    if (ec) return target.string() + ": cannot move the download into place: " + ec.message();
    return std::nullopt;
}

// The dataset's files are all there: hold them to the catalog.
DatasetCheck checkPresent(const DatasetInfo& info, const fs::path& dataDir) {
    std::string why;
    DatasetInfo sizeOnly = info;
    sizeOnly.sha512.clear();
    if (!verifyDataset(sizeOnly, dataDir, &why)) return {DatasetState::Mismatch, why};
    const std::string file = (dataDir / info.file).string();
    if (info.sha512.empty()) return {DatasetState::Ok, file + ": size right; no SHA-512 recorded, not checked"};
    if (verifyDataset(info, dataDir, &why)) {
        if (info.status == "exact") return {DatasetState::Verified, file + ": SHA-512 matches the published digest"};
        return {DatasetState::Verified,
                file + ": SHA-512 matches the recorded digest (" + info.status + " copy, no published digest)"};
    }
    if (info.status == "reconstructed")
        return {DatasetState::Ok, why + "; a reconstructed dataset has no published digest, so not checked"};
    return {DatasetState::Mismatch, why};
}

}  // namespace

std::string_view datasetStateName(DatasetState state) {
    switch (state) {
    case DatasetState::Verified: return "verified";
    case DatasetState::Ok: return "ok";
    case DatasetState::Downloaded: return "downloaded";
    case DatasetState::Missing: return "MISSING";
    case DatasetState::Mismatch: break;
    }
    return "MISMATCH";
}

DatasetCheck checkDataset(const DatasetInfo& info, const fs::path& dataDir, bool download) {
    const fs::path raw = dataDir / info.file;
    const fs::path header = info.header.empty() ? fs::path() : dataDir / info.header;
    const bool rawThere = fs::exists(raw);
    const bool headerThere = header.empty() || fs::exists(header);
    if (rawThere && headerThere) return checkPresent(info, dataDir);
    const std::string absent = !rawThere ? raw.string() : header.string();
    if (!download) return {DatasetState::Missing, absent + ": not there (published at " + info.url + ")"};

    std::error_code ec;
    fs::create_directories(raw.parent_path(), ec);
    if (ec) return {DatasetState::Missing, raw.parent_path().string() + ": cannot create: " + ec.message()};
    if (!headerThere) {
        if (info.headerUrl.empty()) return {DatasetState::Missing, absent + ": not there, and no header_url"};
        if (auto failure = fetchUrl(info.headerUrl, header)) return {DatasetState::Missing, *failure};
    }
    if (rawThere) return checkPresent(info, dataDir);

    // Checked under its temporary name, so that a wrong download never sits where data is looked for.
    DatasetInfo fetched = info;
    fetched.file = fs::path(info.file).replace_filename("." + raw.filename().string() + ".check").string();
    const fs::path checkedName = dataDir / fetched.file;
    if (auto failure = fetchUrl(info.url, checkedName)) return {DatasetState::Missing, *failure};
    DatasetCheck check = checkPresent(fetched, dataDir);
    if (check.state == DatasetState::Mismatch) {
        fs::remove(checkedName, ec);
        return {DatasetState::Mismatch, "downloaded from " + info.url + " but it is not the catalog's file: " +
                                            check.detail + " (removed)"};
    }
    fs::rename(checkedName, raw, ec);
    if (ec) return {DatasetState::Missing, raw.string() + ": cannot move the download into place: " + ec.message()};
    const std::string verdict = check.state == DatasetState::Verified ? "SHA-512 matches the catalog" : check.detail;
    return {DatasetState::Downloaded, raw.string() + " from " + info.url + "; " + verdict};
}

}  // namespace vri
