// vri-sampler-probe: how precisely a Vulkan device's texture unit interpolates, the question behind
// vri-render --interpolation sampler (see SamplerProbe in vulkan_renderer.h).
#include <CLI/CLI.hpp>

#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/core/voxel_type.h"
#include "libvri/report/table.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/csv.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/vulkan/vulkan_renderer.h"

namespace {

constexpr const char* kTool = "vri-sampler-probe";

int run(int argc, char** argv) {
    std::string device, output, summary;
    std::vector<std::string> types{"uint8", "uint16", "float32"};
    bool quiet = false;
    CLI::App app{"Measures a Vulkan device's trilinear texture filtering: for each voxel type, a 2-texel 3D image "
                 "holding 0 and full scale is read at 4097 evenly spaced points between the texel centres, and "
                 "each reading is compared with the exact weight. The error is what the sampler adds to every "
                 "interpolated voxel value, as a fraction of the difference between neighbouring voxels.",
                 kTool};
    app.add_option("--device", device, "Vulkan device: an index of vri-render --list-devices or part of a name");
    vri::addListOption(app, "--types", types, "voxel types to probe, comma separated (uint8: R8 unorm, uint16: R16 "
                                              "unorm, float32: R32 float)");
    app.add_option("-o,--output", output, "CSV of every reading: type, format, weight, read, error ('-': stdout)");
    app.add_option("--summary", summary, "Markdown table per type: reported sub-texel bits, max error, effective "
                                         "bits, distinct readings ('-': stdout)");
    app.add_flag("-q,--quiet", quiet, "no summary lines on stderr");
    app.footer("Examples:\n"
               "  vri-sampler-probe --summary -\n"
               "  vri-sampler-probe --device 0 --types uint8 -o r8.csv --summary r8.md\n"
               "\n"
               "A format the device cannot filter linearly is a row of '-' with the reason under the table. Exit 0 "
               "when at least one type was measured, 1 when none could be (no Vulkan device, no filterable "
               "format), non-zero on a bad argument. Outputs are written atomically.");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;
    vri::requireDistinctOutputs({{"-o", output}, {"--summary", summary}});
    std::vector<vri::VoxelType> voxelTypes;
    for (const std::string& name : types) voxelTypes.push_back(vri::parseVoxelType(name, "--types"));

    vri::VulkanRenderer renderer(device);
    vri::Table table;
    table.title = "Trilinear filtering on Vulkan device '" + renderer.device().name + "' (" + renderer.device().type +
                  ", API " + renderer.device().apiVersion + ")";
    table.rowHeader = "Voxel type (format)";
    table.columns = {"reported sub-texel bits", "max error", "effective bits", "distinct readings"};
    table.precision = {0, 3, 1, 0};
    table.significant = {false, true, false, false};
    std::string csv = vri::csvLine({"type", "format", "weight", "read", "error"});
    int measured = 0;
    for (const vri::VoxelType type : voxelTypes) {
        const std::string name(vri::voxelTypeName(type));
        try {
            const vri::SamplerProbe probe = renderer.probeSampler(type);
            for (std::size_t i = 0; i < probe.weight.size(); ++i)
                csv += vri::csvLine({name, probe.format, vri::exactNumber(probe.weight[i]),
                                     vri::exactNumber(probe.read[i]), vri::exactNumber(probe.read[i] - probe.weight[i])});
            const std::set<double> distinct(probe.read.begin(), probe.read.end());
            table.rows.push_back(name + " (" + probe.format + ")");
            table.cells.push_back({double(probe.subTexelPrecisionBits), probe.maxError, probe.effectiveBits(),
                                   double(distinct.size())});
            ++measured;
            if (!quiet)
                std::cerr << kTool << ": " << name << " (" << probe.format << "): max error " << probe.maxError << ", "
                          << probe.effectiveBits() << " bits, " << distinct.size() << " distinct readings\n";
        } catch (const vri::Error& e) {
            table.rows.push_back(name);
            table.cells.push_back({std::nullopt, std::nullopt, std::nullopt, std::nullopt});
            table.notes.push_back(name + ": " + e.what());
        }
    }
    if (measured == 0) throw vri::Error("no voxel type could be probed: " + table.notes.front());
    table.notes.push_back("Readings at 4097 points between two texels holding 0 and full scale; error = read - "
                          "exact weight, in units of the difference between the texels. Effective bits = "
                          "-log2(max error). Distinct readings: 2^k + 1 when the filter's weights lie on a grid of 1/2^k (257 for "
                          "8 sub-texel bits), more when they are exact.");
    vri::OutputSet files;
    if (!output.empty()) files.add(output, csv);
    if (!summary.empty()) files.add(summary, vri::toMarkdown(table));
    files.write();
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
