#include "libvri/core/adaptive_simpson.h"

#include "libvri/util/error.h"
#include "libvri/util/format.h"

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

}  // namespace vri
