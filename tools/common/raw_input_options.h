#pragma once
// The command-line options every tool that reads volumes shares: how to lay out a headerless raw
// file and how to override a volume's spacing.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "vri/core/volume.h"
#include "vri/io/volume_io.h"

namespace vri {

class RawInputOptions {
public:
    // Adds --dims, --type, --byte-order, --header-bytes and --spacing to `app`.
    void addTo(CLI::App& app);
    // The raw layout the options ask for (nullopt when none is given and the file's name or header
    // must tell); throws vri::Error naming the option that is wrong.
    std::optional<RawLayout> layout(const std::string& input) const;
    // Reads `input` with that layout and applies --spacing.
    Volume read(const std::string& input) const;

private:
    std::string dims_, type_, byteOrder_, spacing_;
    long long headerBytes_ = 0;
    CLI::Option* byteOrderOption_ = nullptr;
    CLI::Option* headerBytesOption_ = nullptr;
};

}  // namespace vri
