// Paper A's four placements against hand-computed tStart, tIncr and sample counts.
#include <doctest/doctest.h>

#include "libvri/core/placement.h"

using namespace vri;
using V = glm::dvec3;

namespace {
const V dim4(4.0);
SampleSchedule<double> place(Placement p, V entry, V exit, V eye = V(-0.3, 0.5, 0.5), double rate = 1.0) {
    return placeSamples<double>(p, entry, exit, eye, dim4, rate);
}
}  // namespace

TEST_CASE("placement: a ray across a 4^3 volume at rate 1") {
    const V entry(0.0, 0.5, 0.5), exit(1.0, 0.5, 0.5);
    SUBCASE("entry align: step = 1 voxel = 0.25 texture units, first sample half a step in") {
        auto s = place(Placement::EntryAlign, entry, exit);
        CHECK(s.tEnd == 1.0);
        CHECK(s.tIncr == 0.25);
        CHECK(s.tStart == 0.125);
        CHECK(s.count == 4);
    }
    SUBCASE("entry-exit align: floor(4) samples fit exactly") {
        auto s = place(Placement::EntryExitAlign, entry, exit);
        CHECK(s.tIncr == 0.25);
        CHECK(s.tStart == 0.125);
        CHECK(s.count == 4);
    }
    SUBCASE("entry-exit-corner align: ceil(rate * |ray * (dim - 1)|) = 3 samples") {
        auto s = place(Placement::EntryExitAlignCorner, entry, exit);
        CHECK(s.tIncr == doctest::Approx(1.0 / 3.0).epsilon(1e-15));
        CHECK(s.tStart == doctest::Approx(1.0 / 6.0).epsilon(1e-15));
        CHECK(s.count == 3);
    }
    SUBCASE("eye align: the eye is 1.2 steps before the entry, so the first sample is 0.8 steps in") {
        auto s = place(Placement::EyeAlign, entry, exit);
        CHECK(s.tIncr == 0.25);
        CHECK(s.tStart == doctest::Approx(0.2).epsilon(1e-12));
        CHECK(s.count == 4);  // t = 0.2, 0.45, 0.7, 0.95
        // Every sample lies on a sphere around the eye at a whole number of steps.
        for (int k = 0; k < s.count; ++k) {
            const double d = (0.3 + s.t(k)) / s.tIncr;
            CHECK(d == doctest::Approx(std::round(d)).epsilon(1e-12));
        }
    }
}

TEST_CASE("placement: a ray of 3.6 voxels") {
    const V entry(0.0, 0.5, 0.5), exit(0.9, 0.5, 0.5);
    auto entryAlign = place(Placement::EntryAlign, entry, exit);
    CHECK(entryAlign.tIncr == doctest::Approx(0.25).epsilon(1e-15));
    CHECK(entryAlign.count == 4);  // t = 0.125 ... 0.875 < 0.9: the last sample overshoots the exit
    auto entryExit = place(Placement::EntryExitAlign, entry, exit);
    CHECK(entryExit.count == 3);
    CHECK(entryExit.tIncr == doctest::Approx(0.3).epsilon(1e-15));
    CHECK(entryExit.tStart == doctest::Approx(0.15).epsilon(1e-15));
    auto corner = place(Placement::EntryExitAlignCorner, entry, exit);
    CHECK(corner.count == 3);  // ceil(2.7)
    CHECK(corner.tIncr == doctest::Approx(0.3).epsilon(1e-15));
}

TEST_CASE("placement: rays shorter than one step") {
    const V entry(0.0, 0.5, 0.5);
    SUBCASE("0.4 voxels: only entry-exit-corner samples it, at its midpoint") {
        const V exit(0.1, 0.5, 0.5);
        CHECK(place(Placement::EyeAlign, entry, exit).count == 0);  // first sample at t = 0.2 > 0.1
        CHECK(place(Placement::EntryAlign, entry, exit).count == 0);
        CHECK(place(Placement::EntryExitAlign, entry, exit).count == 0);
        auto corner = place(Placement::EntryExitAlignCorner, entry, exit);
        CHECK(corner.count == 1);
        CHECK(corner.tIncr == doctest::Approx(0.1).epsilon(1e-15));
        CHECK(corner.tStart == doctest::Approx(0.05).epsilon(1e-15));
    }
    SUBCASE("0.6 voxels: entry align still takes one sample (half a step in), entry-exit takes none") {
        const V exit(0.15, 0.5, 0.5);
        CHECK(place(Placement::EntryAlign, entry, exit).count == 1);
        CHECK(place(Placement::EntryExitAlign, entry, exit).count == 0);
        CHECK(place(Placement::EntryExitAlignCorner, entry, exit).count == 1);
    }
    SUBCASE("a ray that only touches the box has no samples in any placement") {
        for (auto p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                       Placement::EntryExitAlignCorner})
            CHECK(place(p, entry, entry).count == 0);
    }
}

TEST_CASE("placement: entry-exit-corner gives every ray of positive length at least one sample") {
    for (double len : {1e-9, 1e-4, 0.01, 0.2, 0.33, 1.0})
        for (double rate : {0.25, 1.0, 4.0, 16.0}) {
            auto s = place(Placement::EntryExitAlignCorner, V(0.0), V(len, len * 0.5, 0.0), V(-1.0), rate);
            CHECK(s.count >= 1);
            CHECK(s.t(s.count - 1) < s.tEnd);
        }
}

TEST_CASE("placement: counted samples all lie before tEnd") {
    for (auto p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                   Placement::EntryExitAlignCorner})
        for (double rate : {0.3, 1.0, 2.0, 7.0}) {
            auto s = place(p, V(0.1, 0.2, 0.0), V(0.9, 0.7, 1.0), V(-2.0, 0.3, 0.1), rate);
            REQUIRE(s.count > 0);
            CHECK(s.t(0) > 0.0);
            CHECK(s.t(s.count - 1) < s.tEnd);
            if (p == Placement::EyeAlign || p == Placement::EntryAlign) CHECK_FALSE(s.t(s.count) < s.tEnd);
        }
}

TEST_CASE("placement names round-trip and unknown names are rejected") {
    for (auto p : {Placement::EyeAlign, Placement::EntryAlign, Placement::EntryExitAlign,
                   Placement::EntryExitAlignCorner})
        CHECK(parsePlacement(placementName(p), "--placement") == p);
    CHECK_THROWS_WITH_AS(parsePlacement("middle", "--placement"),
                         doctest::Contains("--placement: unknown placement 'middle'"), std::exception);
}
