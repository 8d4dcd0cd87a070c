#pragma once
// The pixels a comparison counts, from its --mask (vri-diff, Python's compare(mask=), an experiment's
// mask:): all, those either image hits above an alpha level, or a mask image's, read from its file.
#include "libvri/core/image.h"
#include "libvri/core/pixel_mask.h"

namespace vri {

// Throws vri::Error when the mask image cannot be read or is not the images' size.
PixelMask pixelMaskFor(const MaskSpec& spec, const Image& a, const Image& b);

}  // namespace vri
