#pragma once
// How busy the machine's other processes kept its cores while this one timed its frames: a time measured
// beside them is inflated, and the tables and charts made from it should say so. Linux's /proc counters:
// all CPUs' busy time (/proc/stat) less this process's own (/proc/self/stat, every thread), over the wall
// time between two samples. Unlike the load average, which follows a minute behind, it covers exactly the
// timed frames.
#include <cstdint>
#include <optional>

namespace vri {

struct CpuSample {
    double wallSeconds = 0;     // a steady clock
    std::uint64_t busyTicks = 0;  // all CPUs: user, nice, system, irq, softirq, steal
    std::uint64_t ownTicks = 0;   // this process: utime + stime of all its threads
};

// Now; nullopt where /proc cannot be read (not Linux).
std::optional<CpuSample> sampleCpu();

// The cores' worth of CPU time that other processes used between the samples (0 when none, about 1 for one
// process spinning); nullopt over less than a quarter of a second, too short for the counters' 10 ms ticks.
std::optional<double> otherProcessCores(const CpuSample& before, const CpuSample& after);

// The cores of this machine that are online.
int onlineCores();

}  // namespace vri
