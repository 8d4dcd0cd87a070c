#include "vri/adaptive_simpson.h"

#include "vri/csv.h"
#include "vri/error.h"
#include "vri/format.h"

namespace vri {

std::string_view acceptedValueName(AcceptedValue v) { return v == AcceptedValue::Richardson ? "richardson" : "paper"; }

AcceptedValue parseAcceptedValue(std::string_view name, const std::string& what) {
    if (name == "richardson") return AcceptedValue::Richardson;
    if (name == "paper") return AcceptedValue::PaperDPlusE;
    throw Error(what + ": unknown accepted value '" + std::string(name) + "' (expected richardson or paper)");
}

void validate(const AdaptiveParameters& p) {
    if (!(p.hMin > 0.0) || !std::isfinite(p.hMin))
        throw Error("h_min must be positive and finite, got " + exactNumber(p.hMin));
    if (!(p.h0 >= p.hMin) || !std::isfinite(p.h0))
        throw Error("the initial step h0 must be finite and at least h_min (" + exactNumber(p.hMin) + "), got " +
                    exactNumber(p.h0));
    if (!(p.hMax >= p.h0))
        throw Error("h_max must be at least the initial step h0 (" + exactNumber(p.h0) + "), got " +
                    exactNumber(p.hMax));
    if (!(p.tolerance >= 0.0) || !std::isfinite(p.tolerance))
        throw Error("the tolerance must be >= 0 and finite, got " + exactNumber(p.tolerance));
}

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
