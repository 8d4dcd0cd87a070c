#include "vri/core/occupancy_cache.h"

#include <algorithm>
#include <chrono>

namespace vri {

bool OccupancyCache::matches(const void* volume, GridConvention convention, const TransferFunction& tf) const {
    const auto same = [](const TransferFunctionPoint& a, const TransferFunctionPoint& b) {
        return a.s == b.s && a.r == b.r && a.g == b.g && a.b == b.b && a.tau == b.tau;
    };
    const auto& p = tf.points();
    return grid_ && volume_.get() == volume && convention_ == convention && emission_ == tf.emission() &&
           std::equal(points_.begin(), points_.end(), p.begin(), p.end(), same);
}

template <class V>
OccupancyCache::Entry OccupancyCache::getFor(const std::shared_ptr<const V>& volume, GridConvention convention,
                                             const TransferFunction& tf) {
    if (matches(volume.get(), convention, tf)) return {*grid_, buildSeconds_, true};
    grid_.reset();
    const auto start = std::chrono::steady_clock::now();
    grid_.emplace(*volume, convention, tf);
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    volume_ = volume;
    convention_ = convention;
    points_ = tf.points();
    emission_ = tf.emission();
    return {*grid_, buildSeconds_, false};
}

OccupancyCache::Entry OccupancyCache::get(const std::shared_ptr<const Volume>& volume, GridConvention convention,
                                          const TransferFunction& tf) {
    return getFor(volume, convention, tf);
}

OccupancyCache::Entry OccupancyCache::get(const std::shared_ptr<const SparseVolume>& volume,
                                          GridConvention convention, const TransferFunction& tf) {
    return getFor(volume, convention, tf);
}

}  // namespace vri
