// blockRanges (the separable min/max behind the occupancy grid and the exact method's empty blocks)
// against the direct scan of every block, on odd sizes where the last block is cut short.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/common.hpp>

#include "libvri/core/block_ranges.h"

using namespace vri;

TEST_CASE("blockRanges equals the direct min and max over every block, margins and clipping included") {
    const glm::ivec3 dims(19, 11, 7);
    std::vector<std::uint16_t> v(static_cast<std::size_t>(dims.x) * dims.y * dims.z);
    std::mt19937 rng(3);
    for (auto& x : v) x = static_cast<std::uint16_t>(rng() % 60000);
    struct Layout {
        int size, before, after;
    };
    for (const Layout l : {Layout{4, 0, 0}, Layout{8, 1, 1}, Layout{3, 2, 0}, Layout{1, 0, 1}}) {
        CAPTURE(l.size);
        const glm::ivec3 blocks = (dims - 1) / l.size + 1;
        const BlockRanges<std::uint16_t> r = blockRanges(v.data(), dims, blocks, l.size, l.before, l.after);
        REQUIRE(r.lo.size() == static_cast<std::size_t>(blocks.x) * blocks.y * blocks.z);
        std::size_t i = 0;
        for (int bz = 0; bz < blocks.z; ++bz)
            for (int by = 0; by < blocks.y; ++by)
                for (int bx = 0; bx < blocks.x; ++bx, ++i) {
                    const glm::ivec3 b(bx, by, bz);
                    const glm::ivec3 lo = glm::max(b * l.size - l.before, glm::ivec3(0));
                    const glm::ivec3 hi = glm::min((b + 1) * l.size + l.after, dims - 1);
                    std::uint16_t mn = 65535, mx = 0;
                    for (int z = lo.z; z <= hi.z; ++z)
                        for (int y = lo.y; y <= hi.y; ++y)
                            for (int x = lo.x; x <= hi.x; ++x) {
                                const std::uint16_t s = v[(static_cast<std::size_t>(z) * dims.y + y) * dims.x + x];
                                mn = std::min(mn, s);
                                mx = std::max(mx, s);
                            }
                    CHECK(r.lo[i] == mn);
                    CHECK(r.hi[i] == mx);
                }
    }
}
