#include "libvri/experiment/plan_waves.h"

#include <algorithm>
#include <map>
#include <optional>

#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// A file one plan reads and another writes.
struct Read {
    std::size_t writer;
    fs::path file;
};

}  // namespace

std::vector<std::vector<std::size_t>> planWaves(const std::vector<Plan>& plans, const std::vector<std::string>& names) {
    std::map<fs::path, std::size_t> writer;
    for (std::size_t p = 0; p < plans.size(); ++p)
        for (const Step& step : plans[p].steps)
            for (const fs::path& out : step.outputs) writer.emplace(out.lexically_normal(), p);
    // Per plan, the other plans it reads from, with one file each.
    std::vector<std::vector<Read>> reads(plans.size());
    for (std::size_t p = 0; p < plans.size(); ++p)
        for (const Step& step : plans[p].steps)
            for (const fs::path& in : step.inputs)
                if (const auto w = writer.find(in.lexically_normal()); w != writer.end() && w->second != p) {
                    bool known = false;
                    for (const Read& r : reads[p]) known = known || r.writer == w->second;
                    if (!known) reads[p].push_back({w->second, w->first});
                }
    std::vector<std::optional<std::size_t>> wave(plans.size());
    std::vector<std::vector<std::size_t>> waves;
    for (std::size_t placed = 0; placed < plans.size();) {
        std::vector<std::size_t> next;
        for (std::size_t p = 0; p < plans.size(); ++p) {
            if (wave[p]) continue;
            bool ready = true;
            for (const Read& r : reads[p]) ready = ready && wave[r.writer] && *wave[r.writer] < waves.size();
            if (ready) next.push_back(p);
        }
        if (next.empty()) {
            // Every plan left reads from another plan left: follow the reads until one comes round.
            std::size_t p = 0;
            while (wave[p]) ++p;
            std::vector<std::size_t> path;
            while (std::find(path.begin(), path.end(), p) == path.end()) {
                path.push_back(p);
                for (const Read& r : reads[p])
                    if (!wave[r.writer]) {
                        p = r.writer;
                        break;
                    }
            }
            const std::size_t a = p;
            const Read& ab =
                *std::find_if(reads[a].begin(), reads[a].end(), [&](const Read& r) { return !wave[r.writer]; });
            throw Error(names[a] + " reads " + ab.file.string() + ", which " + names[ab.writer] + " writes, and " +
                        names[ab.writer] + " reads (in turn) what " + names[a] +
                        " writes: experiments that read each other's results cannot run in one order");
        }
        for (std::size_t p : next) wave[p] = waves.size();
        placed += next.size();
        waves.push_back(std::move(next));
    }
    return waves;
}

}  // namespace vri
