#pragma once
// The data files of paper A's 2D study: the fan of rays (Fig. 2), the error table the paper does
// not give, the placement diagram (Fig. 1) and the field over the square (Fig. 3). CSV with a
// header row, numbers printed to round-trip (%.17g), so the reproducibility check can read them back.
#include <string>
#include <vector>

#include "libvri/core/placement.h"
#include "libvri/core/rays2d.h"
#include "libvri/report/table.h"

namespace vri {

// Every ray's closed form and its discrete sum for each placement at each sampling rate.
struct Fan {
    std::vector<Placement> placements;
    std::vector<double> rates;
    std::vector<Ray2D> rays;
    std::vector<std::vector<std::vector<DiscreteRay>>> discrete;  // [placement][rate][ray]
};
Fan castFan(const Rays2D& study, const std::vector<Placement>& placements, const std::vector<double>& rates);

// "entry-exit_r4": the column of a placement at a rate.
std::string fanColumn(Placement placement, double rate);

// ray, angle_deg, length, closed_form, then per placement and rate the intensity (fanColumn) and
// the sample count (n_ + fanColumn). Rays that miss the square have length 0 and intensity 0.
std::string fanCsv(const Fan& fan);

// One row per placement and rate over the rays of positive length: max and mean |error|, the
// largest over- and underestimate, and the rays left without a sample.
Table fanErrorTable(const Fan& fan);

// Convergence with the sampling rate: one row per rate, columns rate, then PLACEMENT_max and
// PLACEMENT_mean: the max and mean |error| over the rays of positive length (the table's numbers).
std::string convergenceCsv(const Fan& fan);

// Paper A Fig. 1 as line segments and points in the world frame, columns panel, kind, x, y, x2, y2:
// panel "setup" holds the square's outline and the whole fan from the eye (kinds square, fan);
// one panel per placement (its name) holds, for each chosen ray, the square, the ray (ray), its
// samples (sample, a point: x2 = x, y2 = y), the stretch each sample stands for split into the part
// inside the square (covered) and outside it (overshot), the parts of the ray inside the square that
// no sample stands for (missed), and short ticks across the ray at the ends of every stretch (tick).
std::string diagramCsv(const Rays2D& study, const std::vector<int>& rays, const std::vector<Placement>& placements,
                       double rate);

// The field over the square in its own frame on a resolution x resolution grid of points:
// columns x, y, analytic (f = (x + side/2) / side) and reconstructed (from the grid, bilinear).
std::string fieldCsv(const Rays2D& study, int resolution);

}  // namespace vri
