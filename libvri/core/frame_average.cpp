#include "libvri/core/frame_average.h"

#include <algorithm>
#include <vector>

namespace vri {

Image averageFrames(const RenderOptions& options, RenderStats* stats,
                    const std::function<Image(const RenderOptions&, RenderStats*)>& renderFrame) {
    RenderOptions one = options;
    one.frames = 1;
    RenderStats total;
    std::vector<double> sum;
    Image mean;
    for (int f = 0; f < options.frames; ++f) {
        one.seed = options.seed + static_cast<std::uint32_t>(f);  // wraps past 2^32 - 1, as unsigned does
        RenderStats frame;
        Image image = renderFrame(one, &frame);
        if (f == 0) {
            total = frame;
            sum.assign(image.pixels.begin(), image.pixels.end());
            mean = std::move(image);
            continue;
        }
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += image.pixels[i];
        total.samplesPlaced += frame.samplesPlaced;
        total.samplesEvaluated += frame.samplesEvaluated;
        total.raysTerminated += frame.raysTerminated;
        total.terminationLeftOut = std::max(total.terminationLeftOut, frame.terminationLeftOut);
        if (total.preintegration && total.preintegration->largestDelta && frame.preintegration &&
            frame.preintegration->largestDelta) {
            total.preintegration->largestDelta =
                std::max(*total.preintegration->largestDelta, *frame.preintegration->largestDelta);
            for (std::size_t k = 0; k < total.preintegration->lookupsByDelta.size(); ++k)
                total.preintegration->lookupsByDelta[k] += frame.preintegration->lookupsByDelta.at(k);
        }
        total.seconds += frame.seconds;
        total.setupSeconds += frame.setupSeconds;
        total.setupReused = total.setupReused && frame.setupReused;
    }
    const double frames = options.frames;
    for (std::size_t i = 0; i < sum.size(); ++i) mean.pixels[i] = static_cast<float>(sum[i] / frames);
    total.nonfinite = findNonFinitePixels(mean);
    if (stats) *stats = total;
    return mean;
}

}  // namespace vri
