#include "libvri/core/placement.h"

#include "libvri/util/error.h"

namespace vri {

std::string_view placementName(Placement p) {
    switch (p) {
    case Placement::EyeAlign: return "eye";
    case Placement::EntryAlign: return "entry";
    case Placement::EntryExitAlign: return "entry-exit";
    case Placement::EntryExitAlignCorner: break;
    }
    return "entry-exit-corner";
}

Placement parsePlacement(std::string_view name, const std::string& what) {
    for (Placement p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                        Placement::EntryExitAlignCorner})
        if (name == placementName(p)) return p;
    throw Error(what + ": unknown placement '" + std::string(name) +
                "' (expected eye, entry, entry-exit or entry-exit-corner)");
}

}  // namespace vri
