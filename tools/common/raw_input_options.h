#pragma once
// The command-line options every tool that reads volumes shares: how to lay out a headerless raw
// file and how to override a volume's spacing.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "libvri/core/volume.h"
#include "libvri/io/volume_read_options.h"

namespace vri {

class RawInputOptions {
public:
    // Adds --dims, --type, --byte-order, --header-bytes, --spacing and --storage to `app`.
    void addTo(CLI::App& app);
    // The options as given (volume_read_options.h checks and applies them).
    VolumeReadOptions options() const;
    // readVolume(input, options()): the raw layout and --spacing checked and applied.
    Volume read(const std::string& input) const;
    // The same kept as --storage says (auto by default).
    LoadedVolume load(const std::string& input) const;
    VolumeStorage storage() const { return parseVolumeStorage(storage_, "--storage"); }

private:
    std::string dims_, type_, byteOrder_, spacing_, storage_ = "auto";
    long long headerBytes_ = 0;
    CLI::Option* byteOrderOption_ = nullptr;
    CLI::Option* headerBytesOption_ = nullptr;
};

}  // namespace vri
