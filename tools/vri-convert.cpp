// vri-convert: converts volumes between raw, NRRD, Inviwo .dat and OpenVDB, and summarises them.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/cli.h"
#include "common/raw_input_options.h"
#include "libvri/core/volume_stats.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/heartbeat.h"

namespace fs = std::filesystem;

namespace {

std::string text(double value, int digits = 6) {
    std::ostringstream out;
    out << std::setprecision(digits) << value;
    return out.str();
}

std::string text(glm::dvec3 v) { return text(v.x) + " " + text(v.y) + " " + text(v.z); }

// Where the normalisation range comes from, in the order Volume::normalisationRange() tries them.
template <class V>
std::string normalisationSource(const V& volume) {
    if (volume.range) return "from the file";
    return volume.type == vri::VoxelType::Float32 ? "data min..max" : "the type's full range";
}

std::string storageText(const vri::Volume&) { return "dense"; }
std::string storageText(const vri::SparseVolume& volume) {
    return "sparse: " + std::to_string(volume.storedBricks()) + " stored bricks of " +
           std::to_string(vri::SparseVolume::kBlock) + "^3 (with apron), background " + text(volume.background());
}

template <class V>
nlohmann::json infoJson(const fs::path& path, const V& volume, const vri::VolumeStats& stats) {
    const auto array = [](glm::dvec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json j = {{"file", path.string()},
            {"file_bytes", fs::file_size(path)},
            {"dims", {volume.dims.x, volume.dims.y, volume.dims.z}},
            {"voxel_type", vri::voxelTypeName(volume.type)},
            {"spacing", array(volume.spacing)},
            {"origin", array(volume.origin)},
            {"bytes", volume.byteCount()},
            {"data_range", {stats.data.lo, stats.data.hi}},
            {"normalisation_range", {stats.normalisation.lo, stats.normalisation.hi}},
            {"normalisation_source", normalisationSource(volume)},
            {"mean", stats.mean},
            {"zero_fraction", stats.zeroFraction},
            {"active_voxels", stats.activeVoxels},
            {"brick_size", vri::kStatsBrickSize},
            {"bricks", stats.bricks},
            {"active_bricks", stats.activeBricks},
            {"histogram",
             {{"range", {stats.normalisation.lo, stats.normalisation.hi}},
              {"counts", stats.histogram},
              {"below", stats.below},
              {"above", stats.above}}}};
    j["storage"] = std::is_same_v<V, vri::SparseVolume> ? "sparse" : "dense";
    if constexpr (std::is_same_v<V, vri::SparseVolume>) {
        j["stored_bricks"] = volume.storedBricks();
        j["background"] = volume.background();
    }
    return j;
}

template <class V>
void printInfo(const fs::path& path, const V& volume, const vri::VolumeStats& stats) {
    const double voxels = static_cast<double>(volume.voxelCount());
    const auto percent = [&](double count) { return text(100.0 * count / voxels, 3) + "%"; };
    const vri::ValueRange n = stats.normalisation;
    std::cout << "file         " << path.string() << " (" << fs::file_size(path) << " bytes)\n"
              << "dims         " << volume.dims.x << " x " << volume.dims.y << " x " << volume.dims.z << " ("
              << volume.voxelCount() << " voxels)\n"
              << "voxel type   " << vri::voxelTypeName(volume.type) << "\n"
              << "spacing      " << text(volume.spacing) << "\n"
              << "origin       " << text(volume.origin) << "\n"
              << "bytes        " << volume.byteCount() << " in memory, " << storageText(volume) << "\n"
              << "data range   " << text(stats.data.lo) << " .. " << text(stats.data.hi) << "\n"
              << "normalise    " << text(n.lo) << " .. " << text(n.hi) << " (" << normalisationSource(volume) << ")\n"
              << "mean         " << text(stats.mean) << "\n"
              << "zero voxels  " << percent(stats.zeroFraction * voxels) << "\n"
              << "active       " << stats.activeVoxels << " voxels not 0, in " << stats.activeBricks << " of "
              << stats.bricks << " bricks of " << vri::kStatsBrickSize << "^3 ("
              << text(100.0 * static_cast<double>(stats.activeBricks) / static_cast<double>(stats.bricks), 3)
              << "%)\n"
              << "histogram    " << stats.histogram.size() << " bins over " << text(n.lo) << " .. " << text(n.hi)
              << "\n";
    const double width = (n.hi - n.lo) / static_cast<double>(stats.histogram.size());
    for (std::size_t bin = 0; bin < stats.histogram.size(); ++bin) {
        const double count = static_cast<double>(stats.histogram[bin]);
        const std::string bar(static_cast<std::size_t>(std::lround(40.0 * count / voxels)), '#');
        std::cout << "  " << std::setw(10) << text(n.lo + width * static_cast<double>(bin), 4) << "  "
                  << std::setw(10) << stats.histogram[bin] << "  " << std::setw(7) << percent(count) << "  " << bar
                  << "\n";
    }
    if (stats.below + stats.above > 0)
        std::cout << "  outside the range: " << stats.below << " below, " << stats.above << " above\n";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Convert a volume between raw, NRRD (.nhdr/.nrrd), Inviwo .dat and OpenVDB (.vdb), read MetaImage "
                 "(.mhd/.mha) and TIFF stacks (.tif), or summarise it."};
    app.footer(R"(Examples:
  vri-convert bonsai_256x256x256_uint8.raw bonsai.vdb
      dims and type come from the Open SciVis file name; the .vdb stores only non-zero voxels
  vri-convert bonsai.vdb bonsai_256x256x256_uint8.raw
      and back, byte for byte
  vri-convert --info boron.dat
      dims, type, spacing, value range, mean, empty fraction, active voxels and 8^3 bricks, a 16-bin histogram
  vri-convert --info --json bonsai.vdb
  vri-convert scan.raw scan.nhdr --dims 512,512,300 --type uint16 --byte-order big --spacing 0.5,0.5,1

Formats by extension: .nhdr/.nrrd (raw or gzip), .dat (Inviwo), .vdb, .mhd/.mha and .tif/.tiff (read
only); anything else is raw. int8, int16, int32, uint32 and float64 voxels are read as float32 (README.md, "Formats").
Writes are atomic: on failure no output file is left behind.
A volume may take at most 16 GiB in memory (VRI_MAX_BYTES: a byte count to change it). A .vdb whose dims
would unpack to more than 1024 times its file size (and over 256 MiB) is refused unless VRI_MAX_BYTES is set,
or summarised sparse (--storage auto, the default, or sparse: its stored 8^3 bricks only, never the dense box).)");

    std::string input, output, grid;
    vri::RawInputOptions raw;
    bool info = false, json = false, quiet = false;
    app.add_option("input", input,
                   "volume to read: .raw, .nhdr, .nrrd, .dat, .vdb, .mhd, .mha or .tif (a bare name also in $VRI_DATA_DIR)")
        ->required()
        ->transform(vri::volumeInDataDir());
    app.add_option("output", output, "volume to write: .vdb, .nhdr, .nrrd, .dat or .raw (not needed with --info)");
    raw.addTo(app);
    app.add_option("--grid", grid, ".vdb input: the grid to read (default: the first scalar grid)");
    app.add_flag("--info", info, "print a summary of the input: dims, type, spacing, range, mean, histogram");
    app.add_flag("--json", json, "print the summary as JSON on stdout (implies --info)");
    app.add_flag("-q,--quiet", quiet, "no progress on stderr: a line every 5 s of a long read, summary or write "
                                      "(\"vri-convert: writing out.vdb: 10 s\"), and the timing line after a conversion");
    if (auto exitCode = vri::parseArguments(app, "vri-convert", argc, argv)) return *exitCode;

    return vri::guardedMain("vri-convert", [&] {
        if (json) vri::requireUtf8Arguments(argc, argv, "--json names the input, and JSON holds UTF-8 text only");
        info = info || json;
        if (output.empty() && !info) throw vri::Error("give an output file, or --info to summarise the input");

        vri::VolumeReadOptions readOptions = raw.options();
        if (!grid.empty()) readOptions.grid = grid;
        vri::requestedRawLayout(input, readOptions);  // its checks before anything is read or written

        std::vector<vri::OutputArgument> outputs;
        if (!output.empty())
            for (const fs::path& written : vri::filesWrittenBy(output))
                outputs.push_back({written == output ? "output" : "output's raw file", written.string()});
        vri::requireOutputsApartFromInputs(outputs, vri::volumeInputArguments("input", input));

        const vri::VolumeStorage storage = raw.storage();
        const auto start = std::chrono::steady_clock::now();
        const vri::LoadedVolume loaded = [&] {
            const vri::Heartbeat heartbeat("vri-convert: reading " + input, !quiet);
            return vri::readVolume(input, readOptions, storage);
        }();
        const auto read = std::chrono::steady_clock::now();

        if (info) {
            const auto summarise = [&](const auto& volume) {
                const vri::VolumeStats stats = [&] {
                    const vri::Heartbeat heartbeat("vri-convert: summarising " + input, !quiet);
                    return vri::computeVolumeStats(volume);
                }();
                if (json) std::cout << infoJson(input, volume, stats).dump(2) << "\n";
                else printInfo(input, volume, stats);
            };
            if (loaded.sparse) summarise(*loaded.sparse);
            else summarise(*loaded.dense);
        }
        if (!output.empty()) {
            if (loaded.sparse)
                throw vri::Error(input + ": kept sparse (--storage " + std::string(vri::volumeStorageName(storage)) +
                                 "), which only --info reads: convert with --storage dense");
            const vri::Volume& volume = *loaded.dense;
            const auto write = std::chrono::steady_clock::now();
            {
                const vri::Heartbeat heartbeat("vri-convert: writing " + output, !quiet);
                vri::writeVolume(output, volume);
            }
            const auto done = std::chrono::steady_clock::now();
            const auto seconds = [](auto d) { return text(std::chrono::duration<double>(d).count(), 3); };
            // Sizes only of regular files: a device or FIFO output has none.
            std::uintmax_t bytes = 0;
            bool allRegular = true;
            for (const fs::path& written : vri::filesWrittenBy(output)) {
                std::error_code ec;
                allRegular = allRegular && fs::is_regular_file(written, ec);
                if (allRegular) bytes += fs::file_size(written, ec);
            }
            const std::string size = allRegular ? " (" + std::to_string(bytes) + " bytes)" : "";
            if (!quiet)
                std::cerr << "vri-convert: " << output << size << ": read " << seconds(read - start)
                          << " s, wrote " << seconds(done - write) << " s\n";
        }
        return vri::kExitOk;
    });
}
