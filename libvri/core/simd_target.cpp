#include "libvri/core/simd_target.h"

#include <hwy/targets.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <mutex>

#include "libvri/core/engine_environment.h"
#include "libvri/util/error.h"
#include "libvri/util/printable.h"

namespace vri {

namespace {

// The target forced now (empty: Highway's own choice) and its bit, under the mutex.
std::mutex forcedMutex;
std::string forced;
std::int64_t forcedBit = 0;

// Highway's list narrows to the forced target while one is: lift the mask to read the whole list.
// Called with forcedMutex held.
std::vector<std::int64_t> allTargets() {
    if (forcedBit != 0) hwy::DisableTargets(0);
    std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();  // the best (lowest bit) first
    if (forcedBit != 0) hwy::DisableTargets(~forcedBit);
    return targets;
}

std::int64_t targetBit(const std::string& name) {
    for (std::int64_t target : allTargets())
        if (name == hwy::TargetName(target)) return target;
    return 0;
}

}  // namespace

std::vector<std::string> availableSimdTargets() {
    const std::lock_guard lock(forcedMutex);
    std::vector<std::string> names;
    for (std::int64_t target : allTargets()) names.emplace_back(hwy::TargetName(target));
    return names;
}

std::string simdTargetList() {
    std::string list;
    for (const std::string& name : availableSimdTargets()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

std::string simdTargetNamed(std::string_view name) {
    std::string upper(name);
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
    const std::lock_guard lock(forcedMutex);
    return targetBit(upper) != 0 ? upper : std::string();
}

std::string simdTargetFromEnvironment() {
    const char* value = std::getenv(kSimdTargetVariable);
    if (value == nullptr || *value == '\0') return {};
    std::string target = simdTargetNamed(value);
    if (target.empty())
        throw Error(std::string(kSimdTargetVariable) + ": '" + printable(value) + "' is not a SIMD target this CPU and build have (" +
                    simdTargetList() + ")");
    return target;
}

void useSimdTarget(const std::string& target) {
    const std::string wanted = target.empty() ? simdTargetFromEnvironment() : target;
    const std::lock_guard lock(forcedMutex);
    if (wanted == forced) return;
    const std::int64_t bit = wanted.empty() ? 0 : targetBit(wanted);
    if (!wanted.empty() && bit == 0)
        throw Error("SIMD target '" + printable(wanted) + "': not one this CPU and build have");
    // Every other target disabled: the dispatch takes the wanted one, which this CPU runs (the static
    // baseline target, which Highway keeps whatever the mask, is the lowest of all and never wins).
    hwy::DisableTargets(bit == 0 ? 0 : ~bit);
    forced = wanted;
    forcedBit = bit;
}

}  // namespace vri
