#pragma once
// The CPU raycaster: one ray per pixel, parallel over image tiles with oneTBB. Every pixel is
// computed on its own, so the image does not depend on the thread count, bit for bit.
#include "libvri/core/render_contract.h"

namespace vri {

class OccupancyCache;  // occupancy_cache.h

// Throws vri::Error on a non-positive or non-finite sampling rate, bad adaptive parameters, a region that
// is not inside the image, or a log pixel outside the region (the image when there is none).
// With a `cache`, the empty-space grid is kept for the next frame of the same volume and transfer function.
Image render(const Scene& scene, const Camera& camera, const RenderOptions& options, RenderStats* stats = nullptr,
             OccupancyCache* cache = nullptr);

}  // namespace vri
