#pragma once
// The command-line options of the 8-bit PNG preview that every tool writing a render offers:
// --png-exposure, --png-invert and --background (see PngOptions).
#include <string>

#include <CLI/CLI.hpp>

#include "libvri/io/image_io.h"

namespace vri {

class PreviewOptions {
public:
    void addTo(CLI::App& app);
    // Throws vri::Error naming the option that is wrong.
    PngOptions get() const;

private:
    double exposure_ = 1.0;
    bool invert_ = false;
    std::string background_ = "0,0,0";
};

}  // namespace vri
