// Ray/box clipping, grazing and axis-parallel rays included.
#include <doctest/doctest.h>

#include <cmath>

#include "libvri/core/box.h"

using namespace vri;
using V = glm::dvec3;

TEST_CASE("clipRay: a ray through the middle") {
    const Box box{V(0.0), V(1.0)};
    auto r = clipRay(V(-1.0, 0.5, 0.5), V(1.0, 0.0, 0.0), box);
    REQUIRE(r);
    CHECK(r->tNear == 1.0);
    CHECK(r->tFar == 2.0);
}

TEST_CASE("clipRay: axis-parallel rays are decided by the slab, with no 0 * inf") {
    const Box box{V(0.0), V(1.0)};
    CHECK(clipRay(V(-1.0, 1.0, 0.5), V(1.0, 0.0, 0.0), box));       // along the face y = 1: touches
    CHECK_FALSE(clipRay(V(-1.0, 1.0 + 1e-12, 0.5), V(1.0, 0.0, 0.0), box));
    auto edge = clipRay(V(-1.0, 0.0, 0.0), V(1.0, 0.0, 0.0), box);    // along an edge
    REQUIRE(edge);
    CHECK(edge->tNear == 1.0);
    CHECK(edge->tFar == 2.0);
    CHECK_FALSE(clipRay(V(0.5, 0.5, 2.0), V(0.0, 0.0, 1.0), box));    // pointing away
}

TEST_CASE("clipRay: a ray that touches only an edge or a corner hits with zero length") {
    const Box box{V(0.0), V(1.0)};
    const V d = V(1.0, -1.0, 0.0) / std::sqrt(2.0);
    auto edge = clipRay(V(-1.0, 1.0, 0.5), d, box);  // passes the edge x = y = 0 at z = 0.5
    REQUIRE(edge);
    CHECK(edge->tNear == doctest::Approx(std::sqrt(2.0)));
    CHECK(edge->tFar - edge->tNear == doctest::Approx(0.0).epsilon(1e-12));
    CHECK_FALSE(clipRay(V(-1.0, 0.999, 0.5), d, box));
    const V diag = V(1.0, -1.0, -1.0) / std::sqrt(3.0);
    auto corner = clipRay(V(-1.0, 1.0, 1.0), diag, box);  // through the corner (0, 0, 0) only
    REQUIRE(corner);
    CHECK(corner->tFar - corner->tNear == doctest::Approx(0.0).epsilon(1e-12));
}

TEST_CASE("clipRay: an eye inside the box enters at t = 0") {
    const Box box{V(-1.5), V(1.5)};
    auto r = clipRay(V(0.0), V(0.0, 0.0, -1.0), box);
    REQUIRE(r);
    CHECK(r->tNear == 0.0);
    CHECK(r->tFar == 1.5);
}
