#pragma once
// Progressive refinement of jittered sampling (--frames N): the mean of N frames, frame f jittered with
// seed + f (jitter.h), shared by the CPU renderer and the Vulkan backend.
#include <functional>

#include "libvri/core/render_contract.h"

namespace vri {

// Renders options.frames frames through `renderFrame` (each with frames = 1 and its own seed) and returns
// their mean, summed per pixel in double in frame order, so the image is bitwise the same on every run.
// The stats are the first frame's with the work of all frames: samples, wall and setup seconds summed;
// non-finite pixels counted on the mean.
Image averageFrames(const RenderOptions& options, RenderStats* stats,
                    const std::function<Image(const RenderOptions&, RenderStats*)>& renderFrame);

}  // namespace vri
