#include "common/raw_input_options.h"

#include "common/cli.h"

namespace vri {

void RawInputOptions::addTo(CLI::App& app) {
    app.add_option("--dims", dims_, "raw input: X,Y,Z (else taken from NAME_XxYxZ_TYPE.raw)");
    app.add_option("--type", type_, "raw input: uint8, uint16 or float32");
    byteOrderOption_ = app.add_option("--byte-order", byteOrder_, "raw input: little (default) or big");
    headerBytesOption_ = app.add_option("--header-bytes", headerBytes_, "raw input: bytes to skip at the start");
    app.add_option("--spacing", spacing_, "voxel spacing X,Y,Z, overriding what the input says");
}

std::optional<RawLayout> RawInputOptions::layout(const std::string& input) const {
    const bool byteOrderGiven = byteOrderOption_ && byteOrderOption_->count() > 0;
    const bool headerBytesGiven = headerBytesOption_ && headerBytesOption_->count() > 0;
    if (dims_.empty() && type_.empty() && !byteOrderGiven && !headerBytesGiven) return std::nullopt;
    if (dims_.empty() != type_.empty()) throw Error("--dims and --type go together");
    std::optional<RawLayout> layout;
    if (dims_.empty()) {
        layout = layoutFromFileName(input);
        if (!layout)
            throw Error(input + ": --byte-order and --header-bytes need --dims and --type "
                                "(the file name does not give them)");
    } else {
        layout = RawLayout{parseDims(dims_, "--dims"), parseVoxelType(type_, "--type")};
    }
    if (byteOrderGiven) {
        if (byteOrder_ != "little" && byteOrder_ != "big")
            throw Error("--byte-order: expected little or big, got '" + byteOrder_ + "'");
        layout->order = byteOrder_ == "big" ? ByteOrder::Big : ByteOrder::Little;
    }
    if (headerBytes_ < 0) throw Error("--header-bytes: expected a byte count, got " + std::to_string(headerBytes_));
    layout->headerBytes = static_cast<std::size_t>(headerBytes_);
    return layout;
}

Volume RawInputOptions::read(const std::string& input) const {
    Volume volume = readVolume(input, layout(input));
    if (!spacing_.empty()) {
        volume.spacing = parseVec3(spacing_, "--spacing");
        if (!(volume.spacing.x > 0 && volume.spacing.y > 0 && volume.spacing.z > 0))
            throw Error("--spacing: expected positive numbers, got '" + spacing_ + "'");
        requireUsableValues(volume, "--spacing " + spacing_);
    }
    return volume;
}

}  // namespace vri
