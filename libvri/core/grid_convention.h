#pragma once
// Where a volume's samples sit inside its bounding box. Both conventions are in common use and
// they give different images near the border, so every render names the one it used.
#include <string>
#include <string_view>

namespace vri {

enum class GridConvention {
    // Texture style (OpenGL): voxel i is the centre of cell i, at (i + 0.5) / n of the box;
    // outside the outermost centres the sampler clamps to the edge value.
    CellCentred,
    // Voxel i sits at i / (n - 1) of the box: the corner voxels lie on the box corners
    // (paper A, Listing 4's `dim - 1`). Trilinear interpolation then reproduces a linear field exactly.
    NodeCentred,
};

// What the tools assume when none is named (--convention), and so an experiment's scene without one.
inline constexpr GridConvention kDefaultConvention = GridConvention::CellCentred;

std::string_view gridConventionName(GridConvention c);  // "cell" or "node"
GridConvention parseGridConvention(std::string_view name, const std::string& what);

}  // namespace vri
