#include "libvri/io/adaptive_log_csv.h"

#include "libvri/util/csv.h"
#include "libvri/util/format.h"

namespace vri {

std::string adaptiveLogCsv(const std::vector<AdaptiveTry>& log) {
    std::string out = csvLine({"kind", "accepted", "skipped", "t", "h", "t_end", "error", "tolerance", "r", "g", "b", "alpha",
                               "transparency"});
    for (const AdaptiveTry& a : log) {
        const bool integrals = a.kind == AdaptiveTry::Outer && a.accepted;
        const auto value = [&](double x) { return integrals ? exactNumber(x) : std::string(); };
        out += csvLine({a.kind == AdaptiveTry::Inner ? "inner" : "outer", a.accepted ? "1" : "0", a.skipped ? "1" : "0",
                        exactNumber(a.t), exactNumber(a.h), exactNumber(a.t + a.h), exactNumber(a.error), exactNumber(a.tolerance), value(a.r),
                        value(a.g), value(a.b), value(a.alpha), value(a.transparency)});
    }
    return out;
}

}  // namespace vri
