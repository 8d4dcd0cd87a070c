#include "libvri/core/occupancy_cache.h"

#include <algorithm>
#include <chrono>
#include <type_traits>

namespace vri {

void OccupancyCache::key(const std::shared_ptr<const void>& volume, GridConvention convention,
                         const TransferFunction& tf) {
    const auto same = [](const TransferFunctionPoint& a, const TransferFunctionPoint& b) {
        return a.s == b.s && a.r == b.r && a.g == b.g && a.b == b.b && a.tau == b.tau;
    };
    const auto& p = tf.points();
    if (volume_ == volume && convention_ == convention && emission_ == tf.emission() &&
        std::equal(points_.begin(), points_.end(), p.begin(), p.end(), same))
        return;
    grid_.structure.reset();
    exact_.structure.reset();
    stencils_.structure.reset();
    preintegration_.structure.reset();
    preintegrationGrid_.structure.reset();
    preintegrationStencils_.structure.reset();
    volume_ = volume;
    convention_ = convention;
    points_ = p;
    emission_ = tf.emission();
}

template <class Structure, class V, class Invisible>
OccupancyCache::Entry<Structure> OccupancyCache::get(Slot<Structure>& slot, const V& volume,
                                                     GridConvention convention, const Invisible& invisible) {
    if (slot.structure) return {*slot.structure, slot.buildSeconds, true};
    const auto start = std::chrono::steady_clock::now();
    if constexpr (std::is_same_v<Structure, OccupancyGrid> || std::is_same_v<Structure, StencilBricks>)
        slot.structure.emplace(volume, convention, invisible);
    else
        slot.structure.emplace(volume, invisible);
    slot.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return {*slot.structure, slot.buildSeconds, false};
}

OccupancyCache::Entry<OccupancyGrid> OccupancyCache::grid(const std::shared_ptr<const Volume>& volume,
                                                          GridConvention convention, const TransferFunction& tf) {
    key(volume, convention, tf);
    return get(grid_, *volume, convention, tf);
}

OccupancyCache::Entry<OccupancyGrid> OccupancyCache::grid(const std::shared_ptr<const SparseVolume>& volume,
                                                          GridConvention convention, const TransferFunction& tf) {
    key(volume, convention, tf);
    return get(grid_, *volume, convention, tf);
}

OccupancyCache::Entry<ExactEmptySpace> OccupancyCache::exactEmptySpace(const std::shared_ptr<const Volume>& volume,
                                                                       GridConvention convention,
                                                                       const TransferFunction& tf) {
    key(volume, convention, tf);
    return get(exact_, *volume, convention, tf);
}

OccupancyCache::Entry<StencilBricks> OccupancyCache::stencilBricks(const std::shared_ptr<const Volume>& volume,
                                                                   GridConvention convention,
                                                                   const TransferFunction& tf, unsigned octants) {
    key(volume, convention, tf);
    return withOctants(stencils_, get(stencils_, *volume, convention, tf), octants);
}

OccupancyCache::Entry<StencilBricks> OccupancyCache::withOctants(Slot<StencilBricks>& slot, Entry<StencilBricks> entry,
                                                                 unsigned octants) {
    if ((octants & ~entry.structure.octants() & 0xFFu) == 0) return entry;
    const auto start = std::chrono::steady_clock::now();
    slot.structure->addOctants(octants);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The bricks themselves were built by an earlier call if `entry` was reused: this call spent only the octants.
    slot.buildSeconds += seconds;
    return {*slot.structure, entry.reused ? seconds : slot.buildSeconds, false};
}

OccupancyCache::Entry<OccupancyCache::Preintegration> OccupancyCache::preintegration(
    const std::shared_ptr<const Volume>& volume, GridConvention convention, const TransferFunction& tf, double length,
    int size, int order) {
    key(volume, convention, tf);
    if (const TableKey wanted{length, size, order}; !(tableKey_ == wanted)) {
        preintegration_.structure.reset();
        preintegrationGrid_.structure.reset();
        preintegrationStencils_.structure.reset();
        tableKey_ = wanted;
    }
    Slot<Preintegration>& slot = preintegration_;
    if (slot.structure) return {*slot.structure, slot.buildSeconds, true};
    const auto start = std::chrono::steady_clock::now();
    slot.structure.emplace(tf, length, size, order);
    slot.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return {*slot.structure, slot.buildSeconds, false};
}

OccupancyCache::Entry<OccupancyGrid> OccupancyCache::preintegrationGrid(const std::shared_ptr<const Volume>& volume,
                                                                        GridConvention convention,
                                                                        const TransferFunction& tf, double length,
                                                                        int size, int order) {
    const PreintegrationTable& table = preintegration(volume, convention, tf, length, size, order).structure.table;
    return get(preintegrationGrid_, *volume, convention, table);
}

OccupancyCache::Entry<StencilBricks> OccupancyCache::preintegrationStencils(
    const std::shared_ptr<const Volume>& volume, GridConvention convention, const TransferFunction& tf, double length,
    int size, int order, unsigned octants) {
    const PreintegrationTable& table = preintegration(volume, convention, tf, length, size, order).structure.table;
    return withOctants(preintegrationStencils_, get(preintegrationStencils_, *volume, convention, table), octants);
}

}  // namespace vri
