#pragma once
// --allow-nonfinite, offered by the tools that write a render: an image holding NaN or an infinity
// is an error unless asked for; when asked for, a warning on stderr, and the stats count them.
#include <string_view>

#include <CLI/CLI.hpp>

#include "libvri/core/nonfinite_pixels.h"

namespace vri {

class NonFiniteOption {
public:
    void addTo(CLI::App& app);
    // Nothing when every pixel is finite. Otherwise throws vri::Error with found.describe(), or, when
    // allowed, prints "<tool>: warning: ..." on stderr and returns.
    void check(const NonFinitePixels& found, std::string_view tool) const;

private:
    bool allow_ = false;
};

}  // namespace vri
