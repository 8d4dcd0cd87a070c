#pragma once
// The empty-space structures kept from one frame to the next: the fixed-step methods' grid of bricks
// and the packet engine's stencil bricks (occupancy_grid.h), and the exact method's empty cells
// (exact_empty_space.h). Building one reads every voxel (the grid: about 4 % of a float Bonsai frame
// at h = 0.1, of an exact frame at tolerance 3e-8; the stencil bricks with the two octants of
// distances Bonsai's view needs: about 0.07 s, a packet frame at h = 0.5), and a sequence of frames of
// one scene (vri-render --repeat, a camera path) needs it once: like VTK's space-leaping structures it
// is setup, reused while the volume and the transfer function stay, and reported on its own
// (RenderStats and ExactReferenceStats: setupSeconds, setupReused).
#include <memory>
#include <optional>
#include <vector>

#include "libvri/core/exact_empty_space.h"
#include "libvri/core/grid_convention.h"
#include "libvri/core/occupancy_grid.h"
#include "libvri/core/preintegration_table.h"
#include "libvri/core/sparse_volume.h"
#include "libvri/core/transfer_function.h"
#include "libvri/core/volume.h"

namespace vri {

class OccupancyCache {
public:
    template <class Structure>
    struct Entry {
        const Structure& structure;
        double buildSeconds;  // how long building it took, in this call or the one that built it
        bool reused;          // built by an earlier call
    };

    // The structure of this volume, convention and transfer function: the one an earlier call built
    // when all three match (the same Volume object, which the cache holds on to, so its address is
    // never reused for another; equal points and emission), else a new one; a new key drops them all. A
    // Volume is immutable once shared; one changed in place through another pointer is not noticed.
    // Not thread-safe: one cache serves one sequence of renders.
    Entry<OccupancyGrid> grid(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                              const TransferFunction& tf);
    Entry<OccupancyGrid> grid(const std::shared_ptr<const SparseVolume>& volume, GridConvention convention,
                              const TransferFunction& tf);
    Entry<ExactEmptySpace> exactEmptySpace(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                           const TransferFunction& tf);
    // Pre-integration's setup: the table of this transfer function at a segment length, size and order, with
    // its measured error (PreintegrationTable::check), and the grid of the table's own empty space over the
    // volume (null for an analytic field: no grid); another length, size or order builds both again.
    struct Preintegration {
        Preintegration(const TransferFunction& tf, double length, int size, int order)
            : table(tf, length, size, order), error(table.check(tf)) {}
        PreintegrationTable table;
        PreintegrationError error;
    };
    Entry<Preintegration> preintegration(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                         const TransferFunction& tf, double length, int size, int order);
    Entry<OccupancyGrid> preintegrationGrid(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                            const TransferFunction& tf, double length, int size, int order);
    // With the distances of `octants` (rayOctants()) built; building missing ones counts as building.
    Entry<StencilBricks> stencilBricks(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                       const TransferFunction& tf, unsigned octants);
    // The packet engine's bricks of the pre-integration table's own empty space (the table as preintegration()).
    Entry<StencilBricks> preintegrationStencils(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                                const TransferFunction& tf, double length, int size, int order,
                                                unsigned octants);

private:
    template <class Structure>
    struct Slot {
        std::optional<Structure> structure;
        double buildSeconds = 0.0;
    };

    // Keeps the slots when the key is this one, else empties them all and takes it.
    void key(const std::shared_ptr<const void>& volume, GridConvention convention, const TransferFunction& tf);
    // The slot's structure, built from the volume and what says where it is invisible (a transfer function or
    // a pre-integration table) when it has none.
    template <class Structure, class V, class Invisible>
    Entry<Structure> get(Slot<Structure>& slot, const V& volume, GridConvention convention, const Invisible& invisible);
    // `entry`, a slot's, with the distances of `octants` added where missing.
    static Entry<StencilBricks> withOctants(Slot<StencilBricks>& slot, Entry<StencilBricks> entry, unsigned octants);

    std::shared_ptr<const void> volume_;  // a Volume or a SparseVolume
    GridConvention convention_ = GridConvention::CellCentred;
    std::vector<TransferFunctionPoint> points_;
    EmissionModel emission_ = EmissionModel::ColourTimesExtinction;
    Slot<OccupancyGrid> grid_;
    Slot<ExactEmptySpace> exact_;
    Slot<StencilBricks> stencils_;
    Slot<Preintegration> preintegration_;
    Slot<OccupancyGrid> preintegrationGrid_;
    Slot<StencilBricks> preintegrationStencils_;
    struct TableKey {
        double length = 0;
        int size = 0, order = 0;
        bool operator==(const TableKey&) const = default;
    } tableKey_;
};

}  // namespace vri
