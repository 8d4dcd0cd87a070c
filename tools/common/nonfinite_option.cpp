#include "common/nonfinite_option.h"

#include <iostream>

#include "libvri/util/error.h"

namespace vri {

void NonFiniteOption::addTo(CLI::App& app) {
    app.add_flag("--allow-nonfinite", allow_,
                 "write an image whose pixels overflowed to NaN or infinity (with a warning; the stats count them) "
                 "instead of failing");
}

void NonFiniteOption::check(const NonFinitePixels& found, std::string_view tool) const {
    if (found.count == 0) return;
    const std::string what = "the image: " + found.describe() + ": the integration overflowed";
    if (!allow_) throw Error(what + " (a smaller extinction or step, or --allow-nonfinite to write it anyway)");
    std::cerr << tool << ": warning: " << what << '\n';
}

}  // namespace vri
