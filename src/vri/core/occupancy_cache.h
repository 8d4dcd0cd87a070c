#pragma once
// The empty-space grid kept from one frame to the next. Building it reads every voxel (about 4 % of a
// float Bonsai frame at h = 0.1), and a sequence of frames of one scene (vri-render --repeat, a camera
// path) needs it once: like VTK's space-leaping structures it is setup, reused while the volume and
// the transfer function stay, and reported on its own (RenderStats::setupSeconds, setupReused).
#include <memory>
#include <optional>
#include <vector>

#include "vri/core/grid_convention.h"
#include "vri/core/occupancy_grid.h"
#include "vri/core/sparse_volume.h"
#include "vri/core/transfer_function.h"
#include "vri/core/volume.h"

namespace vri {

class OccupancyCache {
public:
    struct Entry {
        const OccupancyGrid& grid;
        double buildSeconds;  // how long building it took, in this call or the one that built it
        bool reused;          // built by an earlier call
    };

    // The grid of this volume, convention and transfer function: the one an earlier call built when
    // all three match (the same Volume object, which the cache holds on to, so its address is never
    // reused for another; equal points and emission), else a new one that replaces it. A Volume is
    // immutable once shared; one changed in place through another pointer is not noticed. Not
    // thread-safe: one cache serves one sequence of renders.
    Entry get(const std::shared_ptr<const Volume>& volume, GridConvention convention, const TransferFunction& tf);
    Entry get(const std::shared_ptr<const SparseVolume>& volume, GridConvention convention, const TransferFunction& tf);

private:
    template <class V>
    Entry getFor(const std::shared_ptr<const V>& volume, GridConvention convention, const TransferFunction& tf);
    bool matches(const void* volume, GridConvention convention, const TransferFunction& tf) const;

    std::shared_ptr<const void> volume_;  // a Volume or a SparseVolume
    GridConvention convention_ = GridConvention::CellCentred;
    std::vector<TransferFunctionPoint> points_;
    EmissionModel emission_ = EmissionModel::ColourTimesExtinction;
    std::optional<OccupancyGrid> grid_;
    double buildSeconds_ = 0.0;
};

}  // namespace vri
