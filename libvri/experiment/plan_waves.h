#pragma once
// The experiments of one vri-run in the order their files allow: an experiment whose step reads a file
// that another experiment's step writes (a figure spec naming ../other/x.csv, a command's input) runs
// after it, so that it reads the file as this run leaves it and its step keys see that file's content.
#include <cstddef>
#include <string>
#include <vector>

#include "libvri/experiment/experiment_plan.h"

namespace vri {

// The plans' indices in waves: wave 0 reads no other plan's outputs, each later wave only outputs of
// earlier waves; each wave in the given order. Throws vri::Error naming both experiments and a file each
// way when two plans read each other's outputs (directly or through others). `names` label the plans.
std::vector<std::vector<std::size_t>> planWaves(const std::vector<Plan>& plans, const std::vector<std::string>& names);

}  // namespace vri
