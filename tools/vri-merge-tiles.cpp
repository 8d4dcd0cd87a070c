// vri-merge-tiles: the tiles of one render (vri-render or vri-reference run with --region) joined into
// the untiled render's image, bit for bit, and one stats record combined field by field; or the layers of
// a brick grid's bricks (vri-render --bricks --brick) joined into the whole volume's image.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "common/cli.h"
#include "common/preview_options.h"
#include "libvri/io/image_io.h"
#include "libvri/io/provenance.h"
#include "libvri/render/layer_merge.h"
#include "libvri/render/tile_merge.h"
#include "libvri/render/tool_flags.h"
#include "libvri/util/atomic_file.h"

namespace {

constexpr const char* kTool = "vri-merge-tiles";

int run(int argc, char** argv) {
    std::vector<std::vector<std::string>> tileArgs, layerArgs;
    std::string output, pngPath, statsPath;
    vri::PreviewOptions preview;

    CLI::App app{"Joins the tiles of one render (vri-render or vri-reference with --region X,Y,WIDTH,HEIGHT) into "
                 "the whole image, bit for bit the untiled render's, and one stats JSON.",
                 kTool};
    auto* parts = app.add_option_group("parts", "what to join (one of)");
    vri::addWordsOption(*parts, vri::merge_flag::tile, tileArgs, "IMAGE.exr STATS.json", 2, 2,
                        "one tile's image and stats (once per tile, any order)");
    vri::addWordsOption(*parts, vri::merge_flag::layer, layerArgs, "IMAGE.exr STATS.json", 2, 2,
                        "one brick's layer and stats (vri-render --bricks --brick; once per brick, any order)");
    parts->require_option(1);
    app.add_option("-o,--output", output, "the whole image (.exr: float RGBA)")->required();
    app.add_option(vri::render_flag::png, pngPath, "8-bit preview PNG of the whole image");
    preview.addTo(app);
    app.add_option(vri::render_flag::stats, statsPath,
                   "the combined statistics and provenance as JSON ('-' for stdout)");
    app.footer(R"(Examples:
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                --region 0,0,800,300 -o top.exr --stats top.json
  vri-reference --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml --size 800x600 \
                --region 0,300,800,300 -o bottom.exr --stats bottom.json
  vri-merge-tiles --tile top.exr top.json --tile bottom.exr bottom.json -o bonsai.exr --stats bonsai.json
  for b in 0,0,0 1,0,0; do vri-render --volume bonsai_256x256x256_uint8.raw --tf experiments/tf/bonsai.yaml \
      --bricks 2,1,1 --brick $b -o layer-$b.exr --stats layer-$b.json; done
  vri-merge-tiles --layer layer-0,0,0.exr layer-0,0,0.json --layer layer-1,0,0.exr layer-1,0,0.json -o bonsai.exr

The tiles must share tool, build, inputs, scene, transfer function, camera and render options, each image
must be its stats' region, and the regions must cover the camera's image exactly once; else one error
line, exit 1. The stats combine the tiles' fields: counts and seconds summed (frame k of the whole is frame
k of every tile, one after another; the median recomputed), maxima and minima kept, mean error bounds
weighted by pixels, properties such as the backend kept when every tile agrees. A field that cannot be
combined is null and named in "not_combined"; "tiles" lists each tile's files, region and command.
Layers must be every brick of one grid once, of one render otherwise; they are joined front to back per
pixel in the order of each ray's bricks, whatever the order given, and the image differs from the unbricked
render by at most the bound the stats' "join" gives (docs/conventions/bricks.md). Outputs are written
atomically, only once every check has passed.)");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    vri::requireUtf8Arguments(argc, argv);
    vri::requireExrOutput({"-o", output});
    const std::vector<vri::OutputArgument> outputs{
        {"-o", output}, {vri::render_flag::png, pngPath}, {vri::render_flag::stats, statsPath}};
    vri::requireDistinctOutputs(outputs);
    const vri::PngOptions png = preview.get();
    std::vector<vri::InputArgument> inputs;
    for (const std::vector<std::string>& t : tileArgs)
        inputs.insert(inputs.end(), {{vri::merge_flag::tile, t[0]}, {vri::merge_flag::tile, t[1]}});
    for (const std::vector<std::string>& l : layerArgs)
        inputs.insert(inputs.end(), {{vri::merge_flag::layer, l[0]}, {vri::merge_flag::layer, l[1]}});
    vri::requireOutputsApartFromInputs(outputs, inputs);
    vri::MergedTiles merged;
    if (!tileArgs.empty()) {
        std::vector<vri::TileFiles> tiles;
        for (const std::vector<std::string>& t : tileArgs) tiles.push_back({t[0], t[1]});
        merged = vri::mergeTiles(tiles);
    } else {
        std::vector<vri::LayerFiles> layers;
        for (const std::vector<std::string>& l : layerArgs) layers.push_back({l[0], l[1]});
        vri::MergedLayers joined = vri::mergeLayers(layers);
        merged = {std::move(joined.image), std::move(joined.record), std::move(joined.metadata)};
    }

    nlohmann::json& record = merged.record;
    record["command"] = vri::commandLine(argc, argv);
    record["time_utc"] = vri::utcTimestamp();
    record["merged_by"] = {{"tool", kTool}, {"build", vri::buildInfo()}, {"machine", vri::machineInfo()}};
    merged.metadata.insert(merged.metadata.begin(), {"vri:command", record["command"]["shell"].get<std::string>()});
    vri::OutputSet files;
    files.add(output, vri::encodeExr(output, merged.image, merged.metadata));
    if (!pngPath.empty()) files.add(pngPath, vri::encodePng(pngPath, merged.image, png));
    if (!statsPath.empty()) files.add(statsPath, record.dump(2) + "\n");
    files.write();
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
