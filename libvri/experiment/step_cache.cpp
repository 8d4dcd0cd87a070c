// Step keys and the records of successful runs that let a later run skip a step.
#include "libvri/experiment/step_cache.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "libvri/core/engine_environment.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

const std::string kMissing = "missing";

void addField(Sha512& hash, const std::string& text) {
    // Length-prefixed, so that no two different field lists hash the same bytes.
    const std::string field = std::to_string(text.size()) + ":" + text;
    hash.update(std::as_bytes(std::span(field.data(), field.size())));
}

std::vector<FileDigest> digestsFromJson(const nlohmann::json& list) {
    std::vector<FileDigest> files;
    for (const nlohmann::json& f : list) files.push_back({f.at("path").get<std::string>(), f.at("sha512").get<std::string>()});
    return files;
}

StepExecution executionFromJson(const nlohmann::json& j) {
    StepExecution e;
    e.executor = j.at("executor").get<std::string>();
    e.node = j.at("node").get<std::string>();
    if (j.contains("job_id")) e.jobId = j.at("job_id").get<std::string>();
    if (j.contains("job_state")) e.jobState = j.at("job_state").get<std::string>();
    if (j.contains("load_average")) {
        e.loadBefore = j.at("load_average").at("before").get<double>();
        e.loadAfter = j.at("load_average").at("after").get<double>();
    }
    if (j.contains("beside")) e.beside = j.at("beside").get<std::vector<std::string>>();
    if (j.contains("earlier_attempts")) e.earlierAttempts = j.at("earlier_attempts").get<std::vector<std::string>>();
    if (j.contains("peak_rss_mib")) e.peakRssMiB = j.at("peak_rss_mib").get<double>();
    return e;
}

}  // namespace

nlohmann::json toJson(const StepExecution& execution) {
    nlohmann::json j = {{"executor", execution.executor}, {"node", execution.node}};
    if (!execution.jobId.empty()) j["job_id"] = execution.jobId;
    if (!execution.jobState.empty()) j["job_state"] = execution.jobState;
    if (execution.loadBefore && execution.loadAfter)
        j["load_average"] = {{"before", *execution.loadBefore}, {"after", *execution.loadAfter}};
    if (!execution.beside.empty()) j["beside"] = execution.beside;
    if (!execution.earlierAttempts.empty()) j["earlier_attempts"] = execution.earlierAttempts;
    if (execution.peakRssMiB) j["peak_rss_mib"] = *execution.peakRssMiB;
    return j;
}

std::optional<double> peakRssMiB(long long kib) {
    if (kib <= 0) return std::nullopt;
    return std::round(static_cast<double>(kib) / 1024.0 * 10.0) / 10.0;
}

nlohmann::json toJson(const std::vector<FileDigest>& files) {
    nlohmann::json list = nlohmann::json::array();
    for (const FileDigest& f : files) list.push_back({{"path", f.path}, {"sha512", f.sha512}});
    return list;
}

const std::string& FileHasher::digest(const fs::path& path) {
    if (auto found = files_.find(path); found != files_.end()) return found->second.digest;
    const std::optional<FileStamp> before = fileStamp(path);  // before the read: a write meanwhile shows later
    Hashed hashed{before ? sha512File(path) : kMissing, before};
    return files_.insert_or_assign(path, std::move(hashed)).first->second.digest;
}

std::optional<FileStamp> FileHasher::stamp(const fs::path& path) const {
    const auto found = files_.find(path);
    return found == files_.end() ? std::nullopt : found->second.stamp;
}

std::vector<std::string> stepKeys(const Plan& plan, const fs::path& toolDir, FileHasher& hasher) {
    std::vector<std::string> keys;
    for (std::size_t i = 0; i < plan.steps.size(); ++i) {
        const Step& step = plan.steps[i];
        Sha512 hash;
        addField(hash, step.tool);
        addField(hash, hasher.digest(toolDir / step.tool));
        addField(hash, std::to_string(step.arguments.size()));
        for (const std::string& argument : step.arguments) addField(hash, argument);
        // What the environment changes in a step's outputs (engine_environment.h): another target or way of
        // loading voxels gives other times and stats, so a run with either is another run.
        for (const auto& [variable, value] : engineEnvironment()) addField(hash, variable + "=" + value);
        for (const fs::path& input : step.inputs) {
            std::string producer;
            for (std::size_t d : plan.dependencies[i])
                for (const fs::path& out : plan.steps[d].outputs)
                    if (out == input) producer = keys[d];
            addField(hash, producer.empty() ? "file " + hasher.digest(input) : "step " + producer);
        }
        keys.push_back(hash.hexDigest());
    }
    return keys;
}

fs::path recordPath(const Plan& plan, const Step& step) { return plan.resultsDir / ".steps" / (step.id + ".json"); }

std::optional<StepRecord> readRecord(const fs::path& path) {
    std::ifstream in(path);
    if (!in) return std::nullopt;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        return StepRecord{j.at("key").get<std::string>(),         j.at("command").get<std::string>(),
                          digestsFromJson(j.at("inputs")),        digestsFromJson(j.at("outputs")),
                          j.at("wall_seconds").get<double>(),     j.at("ran_utc").get<std::string>(),
                          // A record written before records said where steps ran: every step ran locally then.
                          j.contains("execution") ? executionFromJson(j.at("execution"))
                                                  : StepExecution{"local", "unknown", "", "", std::nullopt, std::nullopt, {}}};
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;  // a damaged record is no record: the step runs again
    }
}

void writeRecord(const fs::path& path, const StepRecord& record) {
    const nlohmann::json j = {{"key", record.key},
                              {"command", record.command},
                              {"inputs", toJson(record.inputs)},
                              {"outputs", toJson(record.outputs)},
                              {"wall_seconds", record.wallSeconds},
                              {"ran_utc", record.ranUtc},
                              {"execution", toJson(record.execution)}};
    writeTextFile(path, j.dump(2) + "\n");
}

std::vector<FileDigest> digestFiles(const Plan& plan, const std::vector<fs::path>& files, FileHasher& hasher) {
    std::vector<FileDigest> digests;
    for (const fs::path& file : files) digests.push_back({plan.commandPath(file), hasher.digest(file)});
    return digests;
}

bool recordIsCurrent(const StepRecord& record, const std::string& key, const Plan& plan, const Step& step,
                     FileHasher& hasher) {
    const auto same = [](const std::vector<FileDigest>& a, const std::vector<FileDigest>& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (a[i].path != b[i].path || a[i].sha512 != b[i].sha512 || a[i].sha512 == kMissing) return false;
        return true;
    };
    return record.key == key && same(record.inputs, digestFiles(plan, step.inputs, hasher)) &&
           same(record.outputs, digestFiles(plan, step.outputs, hasher));
}

}  // namespace vri
