#include "libvri/core/brick_layers.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "libvri/util/error.h"

namespace vri {

Image brickLayerImage(int width, int height) {
    Image image(width, height, 5);
    image.channelNames[4] = kBrickOrderChannel;
    return image;
}

namespace {

constexpr double kFloatUnit = 0x1p-24;   // u
constexpr double kDoubleUnit = 0x1p-53;  // u_d

double gamma(double n) { return n * kDoubleUnit / (1.0 - n * kDoubleUnit); }

struct Layer {
    const Image* image;
    std::array<int, 5> channel;  // R, G, B, A, brick_order
};

}  // namespace

double maxSamplesPerRay(double diagonalVoxels, double rate) {
    const double n = std::ceil(diagonalVoxels * rate) + 2;
    return std::isfinite(n) && n > 0 ? std::min(n, kSampleLimitPerRay) : kSampleLimitPerRay;
}

BrickComposite compositeBrickLayers(const std::vector<const Image*>& layers, const std::vector<std::string>& names,
                                    double maxSamples) {
    if (layers.empty()) throw Error("bricks: no layer to join");
    std::vector<Layer> in;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const Image& image = *layers[i];
        Layer layer{&image, {}};
        const char* wanted[5] = {"R", "G", "B", "A", kBrickOrderChannel};
        for (int c = 0; c < 5; ++c) {
            layer.channel[c] = channelIndex(image, wanted[c]);
            if (layer.channel[c] < 0)
                throw Error(names[i] + ": no channel '" + wanted[c] + "' (a brick's layer has R, G, B, A and " +
                            kBrickOrderChannel + ")");
        }
        if (image.width != layers[0]->width || image.height != layers[0]->height)
            throw Error(names[i] + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", but " +
                        names[0] + " is " + std::to_string(layers[0]->width) + "x" + std::to_string(layers[0]->height));
        in.push_back(layer);
    }
    const int m = static_cast<int>(in.size());
    const double g = gamma(2 * maxSamples + 2.0 * m + 2);
    BrickComposite out{Image(layers[0]->width, layers[0]->height), 0.0};
    std::vector<std::pair<float, int>> order;  // (place along the ray, layer) of the layers holding something
    for (int y = 0; y < out.image.height; ++y)
        for (int x = 0; x < out.image.width; ++x) {
            order.clear();
            for (int i = 0; i < m; ++i) {
                const Layer& l = in[i];
                bool something = false;
                for (int c = 0; c < 4; ++c) something = something || l.image->at(x, y, l.channel[c]) != 0.0f;
                if (something) order.emplace_back(l.image->at(x, y, l.channel[4]), i);
            }
            std::sort(order.begin(), order.end());
            for (std::size_t k = 1; k < order.size(); ++k)
                if (order[k].first == order[k - 1].first)
                    throw Error(names[order[k - 1].second] + " and " + names[order[k].second] + " both hold pixel " +
                                std::to_string(x) + "," + std::to_string(y) + " at place " +
                                std::to_string(order[k].first) + " along its ray (layers of one brick grid?)");
            double colour[3] = {0, 0, 0}, transmittance = 1.0;
            std::array<double, 4> ranked{};  // sum over the layers of rank x channel
            for (std::size_t k = 0; k < order.size(); ++k) {
                const Layer& l = in[order[k].second];
                double v[4];
                for (int c = 0; c < 4; ++c) v[c] = l.image->at(x, y, l.channel[c]);
                for (int c = 0; c < 3; ++c) colour[c] += transmittance * v[c];
                transmittance *= 1.0 - v[3];
                for (int c = 0; c < 4; ++c) ranked[c] += static_cast<double>(k + 1) * std::abs(v[c]);
            }
            const double joined[4] = {colour[0], colour[1], colour[2], 1.0 - transmittance};
            for (int c = 0; c < 4; ++c) {
                out.image.at(x, y, c) = static_cast<float>(joined[c]);
                // Alpha is 1 - T, T a product: T's relative rounding (g) is absolute in alpha, in each grouping.
                const double bound = (kFloatUnit + 3 * g) * ranked[c] + (2 * kFloatUnit + g) * std::abs(joined[c]) +
                                     2 * m * kDoubleUnit + (c == 3 ? 2 * g : 0.0);
                out.boundMax = std::max(out.boundMax, bound);
            }
        }
    return out;
}

}  // namespace vri
