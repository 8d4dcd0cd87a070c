#include "libvri/core/grid_convention.h"

#include "libvri/util/error.h"

namespace vri {

std::string_view gridConventionName(GridConvention c) {
    return c == GridConvention::CellCentred ? "cell" : "node";
}

GridConvention parseGridConvention(std::string_view name, const std::string& what) {
    if (name == "cell" || name == "cell-centred" || name == "cell-centered") return GridConvention::CellCentred;
    if (name == "node" || name == "node-centred" || name == "node-centered") return GridConvention::NodeCentred;
    throw Error(what + ": unknown grid convention '" + std::string(name) + "' (expected cell or node)");
}

}  // namespace vri
