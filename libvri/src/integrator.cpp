#include "vri/integrator.h"

#include "vri/error.h"

namespace vri {

std::string_view integratorName(Integrator i) { return i == Integrator::Riemann ? "riemann" : "composite"; }

Integrator parseIntegrator(std::string_view name, const std::string& what) {
    if (name == "riemann") return Integrator::Riemann;
    if (name == "composite") return Integrator::Composite;
    throw Error(what + ": unknown method '" + std::string(name) + "' (expected riemann or composite)");
}

}  // namespace vri
