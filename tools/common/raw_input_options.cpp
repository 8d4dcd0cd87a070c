#include "common/raw_input_options.h"

#include "libvri/core/scene_flags.h"

namespace vri {

void RawInputOptions::addTo(CLI::App& app) {
    app.add_option(scene_flag::dims, dims_, "raw input: X,Y,Z (else taken from NAME_XxYxZ_TYPE.raw)");
    app.add_option(scene_flag::type, type_, "raw input: uint8, uint16 or float32");
    byteOrderOption_ = app.add_option(scene_flag::byteOrder, byteOrder_, "raw input: little (default) or big");
    headerBytesOption_ = app.add_option(scene_flag::headerBytes, headerBytes_, "raw input: bytes to skip at the start");
    app.add_option(scene_flag::spacing, spacing_, "voxel spacing X,Y,Z, overriding what the input says");
    app.add_option(scene_flag::storage, storage_,
                   "dense, sparse (the 8^3 bricks that are not all background; a .vdb read straight into them) or "
                   "auto (sparse for a .vdb too large to unpack densely)")
        ->capture_default_str();
}

VolumeReadOptions RawInputOptions::options() const {
    VolumeReadOptions options;
    options.dims = dims_;
    options.type = type_;
    options.spacing = spacing_;
    if (byteOrderOption_ && byteOrderOption_->count() > 0) options.byteOrder = byteOrder_;
    if (headerBytesOption_ && headerBytesOption_->count() > 0) options.headerBytes = headerBytes_;
    return options;
}

Volume RawInputOptions::read(const std::string& input) const { return readVolume(input, options()); }

LoadedVolume RawInputOptions::load(const std::string& input) const { return readVolume(input, options(), storage()); }

}  // namespace vri
