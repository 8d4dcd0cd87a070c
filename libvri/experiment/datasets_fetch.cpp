// `make data`: checking each catalog dataset in the data directory and fetching what is missing.
#include <functional>
#include <string>
#include <vector>

#include "libvri/experiment/datasets.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/process.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// Downloads url into `target` through writeAtomically: the file appears only once it is complete
// and `accept` (which throws to refuse it) has passed it. Throws vri::Error saying why not.
void fetch(const std::string& url, const fs::path& target, const std::function<void(const fs::path& tmp)>& accept = {}) {
    // -f: an HTTP error is a failure, not a saved error page. "--" ends the options: a URL cannot pass as one.
    std::string name = "curl";
    auto program = findProgram(name);
    if (!program) program = findProgram(name = "wget");
    if (!program) throw Error("neither curl nor wget is installed");
    writeAtomically(target, [&](const fs::path& tmp) {
        const std::vector<std::string> words =
            name == "curl" ? std::vector<std::string>{"curl", "-fsSL", "--retry", "2", "-o", tmp.string(), "--", url}
                           : std::vector<std::string>{"wget", "-q", "-O", tmp.string(), "--", url};
        const ExitStatus status = runProcess(*program, words);
        if (!status.ok()) throw Error("download of " + url + " failed (" + name + " " + status.describe() + ")");
        if (accept) accept(tmp);
    });
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

    if (!headerThere) {  // writeAtomically makes the folders it needs
        if (info.headerUrl.empty()) return {DatasetState::Missing, absent + ": not there, and no header_url"};
        try {
            fetch(info.headerUrl, header);
        } catch (const Error& e) {
            return {DatasetState::Missing, e.what()};
        }
    }
    if (rawThere) return checkPresent(info, dataDir);

    // Checked under its temporary name, so that a wrong download never sits where data is looked for.
    DatasetCheck check{DatasetState::Missing, ""};
    try {
        fetch(info.url, raw, [&](const fs::path& tmp) {
            DatasetInfo fetched = info;
            fetched.file = tmp.lexically_relative(dataDir).string();
            check = checkPresent(fetched, dataDir);
            if (check.state == DatasetState::Mismatch)
                throw Error("downloaded from " + info.url + " but it is not the catalog's file: " + check.detail +
                            " (removed)");
        });
    } catch (const Error& e) {
        return {check.state == DatasetState::Mismatch ? DatasetState::Mismatch : DatasetState::Missing, e.what()};
    }
    const std::string verdict = check.state == DatasetState::Verified ? "SHA-512 matches the catalog" : check.detail;
    return {DatasetState::Downloaded, raw.string() + " from " + info.url + "; " + verdict};
}

}  // namespace vri
