// The Pareto front of points in two coordinates, both minimised.
#include "libvri/report/pareto.h"

#include <algorithm>
#include <cmath>

namespace vri {

std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& points) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (std::isfinite(points[i].first) && std::isfinite(points[i].second)) order.push_back(i);
    // By x, then y: a point is on the front when its y is below every y before it, or when it equals
    // the last point on the front (equal points sort next to each other).
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[a] < points[b]; });
    std::vector<std::size_t> front;
    for (std::size_t i : order)
        if (front.empty() || points[i].second < points[front.back()].second || points[i] == points[front.back()])
            front.push_back(i);
    return front;
}

}  // namespace vri
