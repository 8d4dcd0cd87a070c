#include "libvri/core/simpson_range.h"

#include "libvri/util/format.h"

namespace vri {

std::string SimpsonRange::describe(std::uint64_t rays) const {
    return std::to_string(pixelsBeyond) + " of " + std::to_string(rays) + " pixels took Simpson steps of tau h up to " +
           exactNumber(largest) + ", beyond " + exactNumber(limit) +
           ", where one step may give an alpha or colour above 1 by more than its tolerance controls (growing as "
           "exp(tau h / 48)): a smaller --step or --h-max keeps them meaningful";
}

}  // namespace vri
