#include "libvri/render/pixel_mask_for.h"

#include "libvri/io/image_io.h"

namespace vri {

PixelMask pixelMaskFor(const MaskSpec& spec, const Image& a, const Image& b) {
    switch (spec.kind) {
    case MaskSpec::Kind::All: return fullMask(a.width, a.height);
    case MaskSpec::Kind::Alpha: return alphaMask(a, b, spec.level);
    case MaskSpec::Kind::Image: break;
    }
    return imageMask(readImage(spec.file), a.width, a.height);
}

}  // namespace vri
