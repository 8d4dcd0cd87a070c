#pragma once
// How the steps of a plan that must run become Slurm jobs: which steps share a job (bundles) and
// what each job asks the cluster for. Pure functions of the plan and the last manifest's prices.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"
#include "libvri/experiment/slurm_profile.h"

namespace vri {

// Steps that run one after another in one job, in plan order.
struct JobBundle {
    std::vector<std::size_t> steps;
    double seconds = 0;  // the priced steps' wall times in the last manifest, added
    bool priced = true;  // every step had a price
};

// The steps to run (plan order, which is dependency order) cut into bundles: a step priced at
// `bundleSeconds` or more, or a render or command step with no price (its cost is unknown and may be
// hours), is a job of its own; the others join the bundle before them until it holds `bundleSeconds`
// (an unpriced diff, table or figure counts 1 s). Bundles are contiguous runs of the plan's order,
// so every job depends only on jobs submitted before it. bundleSeconds 0: a job per step.
std::vector<JobBundle> bundleSteps(const Plan& plan, const std::vector<std::size_t>& steps,
                                   const std::vector<std::optional<double>>& prices, double bundleSeconds);

// What one job asks for.
struct JobResources {
    int cpus = 1;           // --cpus-per-task
    long long memoryMiB = 0;  // --mem
    std::optional<long long> minutes;  // --time; none when a step has no price (the partition's default)
};

// CPUs: a step's own --threads N, else `defaultCpus` for a render or command, 1 for the rest (diffs,
// tables and figures are light). Memory: 256 MiB, plus 8 bytes per byte of the step's input files (a
// volume read and converted to float), plus 64 bytes per pixel of its --size (the image's RGBA in
// float and double, the error images); an input not written yet counts nothing. The bundle asks for
// its largest step's. Time: three times the bundle's price plus 10 minutes, rounded up to whole
// minutes: the price may have been measured on more cores than the job gets, and a job past its
// time loses all its work while one that asks too much only waits a little longer.
// A site profile's `kinds` (slurm_profile.h) replace a step's CPUs (unless it sets --threads) and memory
// where they set them, and the
// time of a job whose every step's kind sets one, by the sum of those times.
JobResources jobResources(const Plan& plan, const JobBundle& bundle, int defaultCpus,
                          const std::map<std::string, StepKindResources>& kinds = {});

// The job's name: "vri:<experiment>:<first step>" (+N for the other steps of a bundle).
std::string jobName(const Plan& plan, const JobBundle& bundle);

}  // namespace vri
