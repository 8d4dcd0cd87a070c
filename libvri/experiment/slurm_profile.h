#pragma once
// A site's Slurm profile: the sbatch options every vri job of the site takes (account, partition, QOS,
// constraint, more options) and, per kind of step, what its jobs ask for in place of vri-run's estimate
// (docs/cluster.md, "Site profile"). vri-run reads VRI_SLURM_PROFILE's file, else ~/.config/vri/slurm.yaml
// when there is one:
//
//     account: proj123
//     partition: short
//     qos: normal
//     constraint: avx2
//     cpus: 4                     # what a render or command asks for when it sets no --threads
//     args: [--exclusive]         # more sbatch options, each checked as --slurm-arg's
//     kinds:                      # render, tile, brick, merge, diff, table, figure, command
//       render: {cpus: 8, mem: 4G, time: 120}   # time in minutes, mem in M or G (MiB, GiB)
//       diff: {mem: 1G}
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"

namespace vri {

// What a job asks for a step of one kind, where the profile sets it.
struct StepKindResources {
    std::optional<int> cpus;
    std::optional<long long> memoryMiB, minutes;
};

struct SlurmProfile {
    std::vector<std::string> sbatchArguments;  // account, partition, qos, constraint, then args
    std::optional<int> cpus;
    std::map<std::string, StepKindResources> kinds;
};

// The kinds a profile may name.
inline constexpr const char* kSlurmStepKinds[] = {"render", "tile",  "brick",  "merge",  "outside",
                                                  "diff",   "table", "figure", "command"};

// The profile's kind of a step: merge (vri-merge-tiles), outside (vri-outside and vri-verify, which run a
// renderer of someone else's), tile (--region), brick (--brick), or the step's kind.
std::string slurmStepKind(const Step& step);

// Reads a profile; throws vri::Error "<file>:line:col: ..." on an unknown key, a kind not listed, a value
// of the wrong form, or an sbatch option --slurm-arg would refuse.
SlurmProfile readSlurmProfile(const std::filesystem::path& path);
// VRI_SLURM_PROFILE (which must name a file), else ~/.config/vri/slurm.yaml if it exists, else none.
std::optional<std::filesystem::path> slurmProfilePath();

}  // namespace vri
