// The Pareto front of (time, error) points, both minimised: dominated points, ties, lone points.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "libvri/report/pareto.h"

using vri::paretoFront;
using Points = std::vector<std::pair<double, double>>;
using Indices = std::vector<std::size_t>;

TEST_CASE("pareto: dominated points are left out, the front is ordered by x") {
    const Points points = {{1, 5}, {2, 3}, {3, 4}, {4, 1}, {0.5, 9}, {5, 1}};
    CHECK(paretoFront(points) == Indices{4, 0, 1, 3});  // (3, 4) by (2, 3); (5, 1) by (4, 1)
}

TEST_CASE("pareto: a single point, and none") {
    CHECK(paretoFront({{2, 7}}) == Indices{0});
    CHECK(paretoFront({}).empty());
}

TEST_CASE("pareto: ties") {
    // Equal points: neither is better, both are on the front, in input order.
    CHECK(paretoFront({{2, 3}, {1, 5}, {2, 3}}) == Indices{1, 0, 2});
    CHECK(paretoFront({{1, 1}, {1, 1}}) == Indices{0, 1});
    // As fast and less accurate, or as accurate and slower: dominated.
    CHECK(paretoFront({{1, 2}, {1, 1}}) == Indices{1});
    CHECK(paretoFront({{2, 1}, {1, 1}}) == Indices{1});
    // A point equal to a dominated one is dominated too.
    CHECK(paretoFront({{1, 1}, {2, 2}, {2, 2}}) == Indices{0});
}

TEST_CASE("pareto: points with a non-finite coordinate are neither on the front nor dominate") {
    const double inf = std::numeric_limits<double>::infinity();
    CHECK(paretoFront({{0.5, inf}, {1, 2}, {0.1, std::nan("")}, {inf, 0}}) == Indices{1});
    CHECK(paretoFront({{1, inf}}).empty());
}
