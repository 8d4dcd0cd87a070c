#pragma once
// The runs worth having when two costs are minimised at once, such as time per frame and error:
// shared by the speed-against-accuracy table (its flags) and by figures (the front they draw).
#include <cstddef>
#include <utility>
#include <vector>

namespace vri {

// Indices of the points that no other point dominates (another point <= in both coordinates and < in
// one), ordered by x, then y. Equal points are all kept, in input order: neither dominates the other.
// Points with a non-finite coordinate are left out: they neither lie on the front nor dominate.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& points);

}  // namespace vri
