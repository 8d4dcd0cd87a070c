// Bundles of steps and what their Slurm jobs ask for.
#include "libvri/experiment/slurm_jobs.h"

#include <algorithm>
#include <cmath>
#include <system_error>

#include "libvri/io/volume_io.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

// A render or a command may run for hours: without a price it is never bundled.
bool mayBeLong(const Step& step) { return step.kind == "render" || step.kind == "command"; }

// A tile or a brick of a render: the parts of one image run side by side, each in a job of its own, priced
// or not (bundled, they would run one after another, and the split would buy nothing on a cluster).
bool isRenderPart(const Step& step) {
    const std::string kind = slurmStepKind(step);
    return kind == "tile" || kind == "brick";
}

int stepCpus(const Step& step, int defaultCpus) {
    // Threads 0 is the tools' "all cores": on a cluster, what a step without --threads gets.
    if (step.threads > 0) return step.threads;
    return mayBeLong(step) ? defaultCpus : 1;
}

// In double: an estimate for the scheduler, where a size beyond 2^53 bytes only needs to stay huge.
long long stepMemoryMiB(const Step& step) {
    constexpr double kMiB = 1 << 20;
    double bytes = 256 * kMiB;
    // Voxels the planner counted. A brick holds them as read (1.05 times them at its peak with its layer image,
    // for 2048^3 in 2 x 2 x 2 bricks; results/bricks-slurm.md): asked as 1.5 times them. A whole volume peaked
    // at 1.3 times its bytes (uint8, 1024^3 and 2048^3, double), 1.7 (float, with its skipping grids) and 1.1
    // (Vulkan, the host's copy freed once uploaded): asked as 2 times them.
    if (step.volumeBytes > 0)
        bytes += (step.volumeParts > 1 ? 1.5 : 2.0) * static_cast<double>(step.volumeBytes);
    else
        for (const fs::path& input : step.inputs) {
            std::error_code ec;
            const std::uintmax_t size = fs::file_size(input, ec);
            // A brick of a raw file reads its share and a ghost layer, (w + 1)^3 / w^3 of the share for bricks w
            // voxels wide: at most 2.4 times it from w = 3 on, asked as 3 times. Narrower bricks (8 times the
            // share at w = 1) stay within the 8 bytes asked a voxel byte, of which a brick uses about 1.5. Other
            // formats are read whole.
            const bool share = step.volumeParts > 1 && !describesItsLayout(input);
            if (!ec) bytes += 8.0 * static_cast<double>(size) * (share ? std::min(1.0, 3.0 / step.volumeParts) : 1.0);
        }
    bytes += 64.0 * static_cast<double>(step.pixels);
    // A renderer of someone else's holds what vri cannot estimate, a browser's processes among them: three.js in
    // headless Chromium held 1.1 GiB at 40 x 30 pixels (the sum of its processes' resident memory, which
    // jobacct_gather counts). At least 2 GiB, which a profile's `outside` kind replaces.
    if (slurmStepKind(step) == "outside") bytes = std::max(bytes, 2048 * kMiB);
    return static_cast<long long>(std::ceil(std::min(bytes, 1e18) / kMiB));
}

}  // namespace

std::vector<JobBundle> bundleSteps(const Plan& plan, const std::vector<std::size_t>& steps,
                                   const std::vector<std::optional<double>>& prices, double bundleSeconds) {
    std::vector<JobBundle> bundles;
    JobBundle open;  // small steps gathering
    const auto close = [&] {
        if (!open.steps.empty()) bundles.push_back(std::move(open));
        open = {};
    };
    for (std::size_t i : steps) {
        const std::optional<double> price = i < prices.size() ? prices[i] : std::nullopt;
        const bool alone = isRenderPart(plan.steps[i]) ||
                           (price ? *price >= bundleSeconds : mayBeLong(plan.steps[i]) || bundleSeconds <= 0);
        if (alone) {
            // Bundles stay contiguous in plan order, so that no job waits for one submitted after it.
            close();
            bundles.push_back({{i}, price.value_or(0), price.has_value()});
            continue;
        }
        open.steps.push_back(i);
        open.seconds += price.value_or(1);
        open.priced = open.priced && price.has_value();
        if (open.seconds >= bundleSeconds) close();
    }
    close();
    return bundles;
}

JobResources jobResources(const Plan& plan, const JobBundle& bundle, int defaultCpus,
                          const std::map<std::string, StepKindResources>& kinds) {
    JobResources resources;
    long long kindMinutes = 0;
    bool everyKindTimed = true;
    for (std::size_t i : bundle.steps) {
        const Step& step = plan.steps[i];
        const auto found = kinds.find(slurmStepKind(step));
        const StepKindResources site = found == kinds.end() ? StepKindResources{} : found->second;
        // A step's own --threads is what it runs on: no profile changes it.
        resources.cpus =
            std::max(resources.cpus, step.threads > 0 ? step.threads : site.cpus.value_or(stepCpus(step, defaultCpus)));
        resources.memoryMiB = std::max(resources.memoryMiB, site.memoryMiB.value_or(stepMemoryMiB(step)));
        everyKindTimed = everyKindTimed && site.minutes;
        kindMinutes += site.minutes.value_or(0);
    }
    if (everyKindTimed && !bundle.steps.empty())
        resources.minutes = kindMinutes;
    else if (bundle.priced)
        resources.minutes = static_cast<long long>(std::ceil((3 * bundle.seconds + 600) / 60));
    return resources;
}

std::string jobName(const Plan& plan, const JobBundle& bundle) {
    std::string name = "vri:" + plan.resultsDir.filename().string() + ":" + plan.steps.at(bundle.steps.front()).id;
    if (bundle.steps.size() > 1) name.append(1, '+').append(std::to_string(bundle.steps.size() - 1));
    return name;
}

}  // namespace vri
