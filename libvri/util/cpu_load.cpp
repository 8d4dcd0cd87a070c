#include "libvri/util/cpu_load.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>

namespace vri {

std::optional<CpuSample> sampleCpu() {
    CpuSample sample;
    sample.wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    std::ifstream stat("/proc/stat");
    std::string cpu;
    std::uint64_t user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    if (!(stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || cpu != "cpu")
        return std::nullopt;
    sample.busyTicks = user + nice + system + irq + softirq + steal;
    // /proc/self/stat: the command (in parentheses, which may hold spaces) and then fields 3 on; utime and
    // stime are fields 14 and 15.
    std::ifstream self("/proc/self/stat");
    std::string line;
    if (!std::getline(self, line)) return std::nullopt;
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos) return std::nullopt;
    std::istringstream fields(line.substr(close + 2));
    std::string field;
    for (int i = 3; i <= 13 && fields >> field; ++i) {
    }
    std::uint64_t utime = 0, stime = 0;
    if (!(fields >> utime >> stime)) return std::nullopt;
    sample.ownTicks = utime + stime;
    return sample;
}

std::optional<double> otherProcessCores(const CpuSample& before, const CpuSample& after) {
    // The counters tick 100 times a second: over less than a quarter of a second they say little.
    const double wall = after.wallSeconds - before.wallSeconds;
    if (!(wall >= 0.25)) return std::nullopt;
    const double ticksPerSecond = static_cast<double>(sysconf(_SC_CLK_TCK));
    const double busy = static_cast<double>(after.busyTicks - before.busyTicks);
    const double own = static_cast<double>(after.ownTicks - before.ownTicks);
    return std::max(0.0, (busy - own) / ticksPerSecond / wall);
}

int onlineCores() { return std::max(1, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN))); }

}  // namespace vri
