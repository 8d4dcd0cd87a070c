#include "libvri/experiment/timing_defaults.h"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "libvri/core/render_option_table.h"

namespace vri {

namespace {

// The runs whose time `table` reports, none when it reports no time.
std::set<std::string> timedRuns(const TableSpec& table, const Experiment& experiment) {
    std::set<std::string> runs;
    if (table.layout == "tradeoff") {
        for (const ComparisonSpec& c : experiment.comparisons)
            if (std::ranges::count(table.comparisons, c.group) > 0) runs.insert(c.run);
    } else if (table.layout == "matrix" && table.value.find("seconds") != std::string::npos) {
        runs.insert(table.runs.begin(), table.runs.end());
    }
    return runs;
}

const std::string* optionValue(const RunSpec& run, const std::string& flag) {
    const auto found = std::ranges::find(run.options, flag, &ToolOption::first);
    return found == run.options.end() ? nullptr : &found->second;
}

}  // namespace

void applyTimingDefaults(Experiment& experiment) {
    const std::string warmUpFlag(findRenderOption("warm_up")->flag()), repeatFlag(findRenderOption("repeat")->flag());
    std::set<std::string> done;
    for (const TableSpec& table : experiment.tables) {
        std::vector<std::string> oneFrame;  // the table's runs timed on one frame
        for (const std::string& id : timedRuns(table, experiment)) {
            const auto run = std::ranges::find(experiment.runs, id, &RunSpec::id);
            if (run == experiment.runs.end()) continue;
            if (done.insert(id).second) {
                std::string filled;
                if (!optionValue(*run, warmUpFlag)) {
                    run->options.emplace_back(warmUpFlag, std::to_string(kTimedWarmUp));
                    filled += "warm_up " + std::to_string(kTimedWarmUp);
                }
                if (!optionValue(*run, repeatFlag)) {
                    run->options.emplace_back(repeatFlag, std::to_string(kTimedFrames));
                    filled += (filled.empty() ? "" : " and ") + std::string("repeat ") + std::to_string(kTimedFrames);
                }
                if (!filled.empty())
                    experiment.defaults.push_back("run '" + id + "': " + filled + ", as its time is tabulated");
            }
            if (const std::string* repeat = optionValue(*run, repeatFlag); repeat && *repeat == "1")
                oneFrame.push_back(id);
        }
        if (!oneFrame.empty())
            experiment.warnings.push_back(
                "table '" + table.name + "' reports the time of " +
                (oneFrame.size() == 1 ? "run '" + oneFrame.front() + "'"
                                      : std::to_string(oneFrame.size()) + " runs ('" + oneFrame.front() + "', ...)") +
                " from one frame (repeat: 1): one sample, which varies by tens of % from run to run");
    }
}

}  // namespace vri
