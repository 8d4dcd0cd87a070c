#include "libvri/core/integrator.h"

#include "libvri/util/error.h"

namespace vri {

namespace {
constexpr Integrator kIntegrators[] = {Integrator::Riemann, Integrator::Composite, Integrator::Simpson,
                                       Integrator::Coupled, Integrator::Decoupled, Integrator::Preintegrated};
}  // namespace

std::string_view integratorName(Integrator i) {
    switch (i) {
    case Integrator::Riemann: return "riemann";
    case Integrator::Composite: return "composite";
    case Integrator::Simpson: return "simpson";
    case Integrator::Coupled: return "coupled";
    case Integrator::Decoupled: return "decoupled";
    case Integrator::Preintegrated: break;
    }
    return "preintegrated";
}

Integrator parseIntegrator(std::string_view name, const std::string& what) {
    for (Integrator i : kIntegrators)
        if (name == integratorName(i)) return i;
    throw Error(what + ": unknown method '" + std::string(name) +
                "' (expected riemann, composite, simpson, coupled, decoupled or preintegrated)");
}

}  // namespace vri
