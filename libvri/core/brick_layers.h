#pragma once
// A brick's render is a layer: per pixel, the premultiplied colour and alpha of the samples it owns (R, G,
// B, A) and the place of its run among the ray's bricks (kBrickOrderChannel, brick_sampler.h). Layers are
// joined front to back per pixel in that order, whatever the order the layers come in, so that the image
// is the same bits for any split of a brick grid among jobs, machines or tiles.
//
// Against the whole volume's render: every sample's colour and alpha are the same bits (the samples and
// their scalars are the whole ray's), and only the sums are grouped differently. A channel v of the joined
// image differs from the whole render's by at most
//     (u + 3 g) sum_b r_b v_b + (2 u + g) v + 2 m u_d   (+ 2 g for alpha),
// the layers b of the pixel ranked r_b = 1 .. m along the ray, u = 2^-24 (a layer's and the image's float
// channels), u_d = 2^-53 and g = gamma_(2N + 2m + 2) = (2N + 2m + 2) u_d / (1 - (2N + 2m + 2) u_d) for the
// double sums of up to N samples a ray (colours and alpha are >= 0, so a sum's rounding is relative to the
// sum itself): a layer's channels are float roundings of double sums
// (u + g relative), a transmittance 1 - A is exact to u_d, the product of the layers' transmittances in
// front of layer b is off by at most (r_b - 1)(u + u_d), the joining and the whole render's own sums by g,
// and both images round to float at the end (u each). Alpha is 1 - T, T a product of up to N factors
// whose relative rounding g is absolute in alpha, once in each grouping. The bound is computed per pixel
// and channel.
#include <string>
#include <vector>

#include "libvri/core/image.h"

namespace vri {

inline constexpr const char* kBrickOrderChannel = "brick_order";

// An RGBA image with a zero brick_order channel: the layer a brick render fills.
Image brickLayerImage(int width, int height);

struct BrickComposite {
    Image image;            // RGBA
    double boundMax = 0.0;  // the largest bound above over the pixels and channels
};

// The most samples a ray of the render takes: its longest ray, the box's diagonal in voxels, at `rate`
// samples a voxel, and the two a placement may add; render_contract.h's limit of 1e9 otherwise.
double maxSamplesPerRay(double diagonalVoxels, double rate);
inline constexpr double kSampleLimitPerRay = 1e9;

// Joins the layers, whose rays take at most `maxSamples` samples; `names` name them in messages. Throws
// vri::Error when a layer lacks a channel, the sizes differ, or two layers with something in a pixel claim
// the same place along its ray.
BrickComposite compositeBrickLayers(const std::vector<const Image*>& layers, const std::vector<std::string>& names,
                                    double maxSamples = kSampleLimitPerRay);

}  // namespace vri
