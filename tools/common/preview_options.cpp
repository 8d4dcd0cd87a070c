#include "common/preview_options.h"

#include "common/cli.h"
#include "libvri/core/scene_flags.h"
#include "libvri/util/format.h"

namespace vri {

void PreviewOptions::addTo(CLI::App& app) {
    app.add_option(scene_flag::pngExposure, exposure_, "preview: multiply colours by this")->capture_default_str();
    app.add_flag(scene_flag::pngInvert, invert_, "preview: 1 - colour (darker = higher intensity)");
    app.add_option(scene_flag::background, background_, "preview: background colour R,G,B")->capture_default_str();
}

PngOptions PreviewOptions::get() const {
    if (!(exposure_ > 0.0)) throw Error("--png-exposure: must be > 0, got " + exactNumber(exposure_));
    PngOptions png;
    png.exposure = static_cast<float>(exposure_);
    png.invert = invert_;
    const glm::dvec3 bg = parseVec3(background_, scene_flag::background);
    png.background = {float(bg.x), float(bg.y), float(bg.z)};
    return png;
}

}  // namespace vri
