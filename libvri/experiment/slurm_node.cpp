// The node side of the Slurm executor: a job's steps, and the shared-file-system check.
#include "libvri/experiment/slurm_node.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "libvri/io/provenance.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/input_digest.h"
#include "libvri/util/json_file.h"
#include "libvri/util/process.h"
#include "libvri/util/sha512.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

std::string jobIdHere() {
    const char* id = std::getenv("SLURM_JOB_ID");
    return id ? id : "";
}

void writeJson(const fs::path& file, const nlohmann::json& j) { writeTextFile(file, j.dump(2) + "\n"); }

}  // namespace

void writeNodeSteps(const fs::path& file, const NodeSteps& steps) {
    nlohmann::json list = nlohmann::json::array();
    for (const NodeStep& s : steps.steps)
        list.push_back({{"id", s.id},
                        {"program", s.program.string()},
                        {"words", s.words},
                        {"log", s.log.string()},
                        {"status", s.status.string()}});
    writeJson(file,
              {{"work_dir", steps.workDir.string()}, {"steps", list}, {"digest_record", steps.digestRecord.string()}});
}

NodeSteps readNodeSteps(const fs::path& file) {
    const nlohmann::json j = readJsonFile(file);
    return readingJsonOf(file, [&] {
        NodeSteps steps{j.at("work_dir").get<std::string>(), {}, j.value("digest_record", std::string())};
        for (const nlohmann::json& s : j.at("steps"))
            steps.steps.push_back({s.at("id").get<std::string>(), s.at("program").get<std::string>(),
                                   s.at("words").get<std::vector<std::string>>(), s.at("log").get<std::string>(),
                                   s.at("status").get<std::string>()});
        return steps;
    });
}

std::optional<NodeStepStatus> readNodeStepStatus(const fs::path& file) {
    // Written atomically (rename), so a file that is there is whole.
    if (!fs::is_regular_file(file)) return std::nullopt;
    const nlohmann::json j = readJsonFile(file);
    return readingJsonOf(file, [&] {
        return NodeStepStatus{j.at("exited").get<bool>(),      j.at("code").get<int>(),
                              j.at("signal").get<int>(),       j.at("wall_seconds").get<double>(),
                              j.at("node").get<std::string>(), j.at("job_id").get<std::string>(),
                              j.value("peak_rss_kib", 0LL)};  // 0: a status of a runner before it
    });
}

int runNodeSteps(const fs::path& file) {
    const NodeSteps steps = readNodeSteps(file);
    // The commands name their files relative to the folder vri-run ran in, the same path here.
    if (::chdir(steps.workDir.c_str()) != 0)
        throw Error(steps.workDir.string() + ": cannot enter it on node " + hostName() + ": " + std::strerror(errno));
    const std::string node = hostName(), jobId = jobIdHere();
    if (!steps.digestRecord.empty()) ::setenv(kInputDigestsVariable, steps.digestRecord.c_str(), 1);
    // Seconds since the epoch, for ordering steps across nodes (whose clocks Slurm needs in step anyway).
    const auto epoch = [] { return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count(); };
    for (const NodeStep& step : steps.steps) {
        const double started = epoch();
        const auto start = std::chrono::steady_clock::now();
        const ExitStatus status =
            runProcess(step.program, step.words, {.in = "/dev/null", .out = step.log, .err = {}, .errToOut = true});
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        writeJson(step.status, {{"exited", status.exited},
                                {"code", status.code},
                                {"signal", status.signal},
                                {"wall_seconds", seconds},
                                {"started_epoch", started},
                                {"ended_epoch", epoch()},
                                {"node", node},
                                {"job_id", jobId},
                                {"peak_rss_kib", status.peakRssKiB}});
        if (!status.ok()) return 1;  // the steps after it may need its outputs: vri-run reports the failure
    }
    return 0;
}

void writeNodeCheck(const fs::path& file, const NodeCheck& check) {
    nlohmann::json tools = nlohmann::json::array(), files = nlohmann::json::array();
    for (const auto& [path, sha] : check.tools) tools.push_back({{"path", path.string()}, {"sha512", sha}});
    for (const auto& [path, size] : check.files) files.push_back({{"path", path.string()}, {"size", size}});
    writeJson(file, {{"token", check.token}, {"tools", tools}, {"files", files}, {"report", check.report.string()}});
}

int runNodeCheck(const fs::path& file) {
    const nlohmann::json j = readJsonFile(file);
    const std::string node = hostName();
    std::vector<std::string> problems;
    const fs::path report = readingJsonOf(file, [&] {
        for (const nlohmann::json& t : j.at("tools")) {
            const fs::path path = t.at("path").get<std::string>();
            std::error_code ec;
            if (!fs::is_regular_file(path, ec))
                problems.push_back(path.string() + ": no such file on node " + node);
            else if (sha512File(path) != t.at("sha512").get<std::string>())
                problems.push_back(path.string() + ": differs on node " + node + " from vri-run's host (SHA-512)");
        }
        for (const nlohmann::json& f : j.at("files")) {
            const fs::path path = f.at("path").get<std::string>();
            std::error_code ec;
            const std::uintmax_t size = fs::file_size(path, ec);
            if (ec)
                problems.push_back(path.string() + ": no such file on node " + node);
            else if (size != f.at("size").get<std::uintmax_t>())
                problems.push_back(path.string() + ": " + std::to_string(size) + " bytes on node " + node + ", " +
                                   std::to_string(f.at("size").get<std::uintmax_t>()) + " on vri-run's host");
        }
        return fs::path(j.at("report").get<std::string>());
    });
    writeJson(report, {{"token", j.at("token")}, {"node", node}, {"problems", problems}});
    return 0;  // the report says what is wrong; a job that failed wrote none
}

std::vector<std::string> readNodeCheckReport(const NodeCheck& check) {
    const fs::path root = check.report.parent_path().parent_path();  // <results>/.slurm-check/<token>.report.json
    if (!fs::is_regular_file(check.report))
        throw Error(root.string() + ": the Slurm check job could not leave its report in this results folder: the "
                                    "compute nodes must see it, the tools and the inputs at the same paths as this host "
                                    "(a shared file system) and be able to write into it");
    const nlohmann::json j = readJsonFile(check.report);
    return readingJsonOf(check.report, [&] {
        if (j.at("token").get<std::string>() != check.token)
            throw Error(check.report.string() + ": a report of another run; the results folder is not the one the "
                                                "compute node wrote into");
        return j.at("problems").get<std::vector<std::string>>();
    });
}

}  // namespace vri
