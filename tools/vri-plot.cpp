// vri-plot: a figure (PNG + SVG) drawn by gnuplot from a YAML spec and CSV data, with the
// generated gnuplot script kept beside it.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/render/tool_flags.h"
#include "libvri/report/plot.h"

namespace {

constexpr const char* kTool = "vri-plot";

int run(int argc, char** argv) {
    std::string specPath, output, dataDir;
    bool scriptOnly = false;
    CLI::App app{"Draws a figure with gnuplot from a YAML spec that names CSV files and columns: writes FIG.png, "
                 "FIG.svg and FIG.gp, the gnuplot script, so that `gnuplot FIG.gp` redraws it by hand.",
                 kTool};
    app.add_option("SPEC", specPath, "figure spec (YAML)")->required();
    app.add_option("-o,--output", output, "the figure, FIG.png (FIG.svg and FIG.gp are written beside it)")->required();
    app.add_option(vri::plot_flag::dataDir, dataDir, "where relative data paths start (default: the spec's folder)")
        ->check(CLI::ExistingDirectory);
    app.add_flag("--script-only", scriptOnly, "write FIG.gp only (no gnuplot needed)");
    app.footer(
        "Spec (relative data paths start at the spec's folder, or at --data-dir):\n"
        "  title: Time against error, Bonsai     # optional\n"
        "  size: [1200, 900]                     # optional, pixels\n"
        "  grid: [2, 2]                          # optional, panel rows x columns\n"
        "  panels:                               # or one panel's keys (x, y, key, ..., series) at the top\n"
        "    - title: CPU\n"
        "      x: {label: seconds per frame, log: true, ticks: data}  # ticks: data: one at every value drawn\n"
        "      y: {label: max error, log: true, range: [1e-6, 1]}\n"
        "      key: top right                    # top/bottom left/right, outside (right), below, off\n"
        "      reference_slopes: [1, 2, 4]       # log x and y: grey dashed y ~ x^k through the rightmost point\n"
        "      pareto: true                      # mark points not dominated in (x, y), both minimised\n"
        "      aspect: equal                     # optional: x and y units equally long (default: auto)\n"
        "      labels: [{x: 0.1, y: 0.5, text: coarse}]  # optional free text, starting at (x, y)\n"
        "      series:\n"
        "        - {file: riemann.csv, x: seconds, y: error, style: linespoints, label: Riemann}\n"
        "        - {file: hist.csv, y: R, style: histogram, label: R}  # vri-diff --histogram bins\n"
        "    - title: error over the square\n"
        "      colorbar: {label: error, min: 0, max: 1, palette: viridis}  # optional, as is each key\n"
        "      series:\n"
        "        - {file: f.csv, x: u, y: v, z: error, style: heatmap}  # rows: a regular grid, any order\n"
        "    - title: samples along a ray\n"
        "      series:\n"
        "        - {file: spans.csv, x: t0, y: row, x2: t1, y2: row, style: segments, width: 3}\n"
        "        - {file: samples.csv, x: t, y: row, style: points, size: 1.5, point: square}\n"
        "  styles: line, dashed, dotted, points, linespoints, histogram, heatmap (needs z),\n"
        "          segments (from x, y to x2, y2)\n"
        "  color: \"#rrggbb\", label: optional; a heatmap takes neither, its colour bar keys it\n"
        "  width (line width): optional, for line, dashed, dotted, linespoints, segments\n"
        "  size, point (circle, square, cross, triangle): optional, for points and linespoints\n"
        "  label: \"\" leaves a series out of the key (default: its y column)\n"
        "  where: {COLUMN: TEXT, ...}: optional, only the rows whose columns hold these texts (TEXT* a prefix);\n"
        "         a series that keeps no row is drawn in the key alone, with a warning; optional: true drops\n"
        "         it instead (a series only some hosts or runs have; a panel with none left is an error)\n"
        "  palette: viridis (default), gray, diverging (blue, white, red)\n"
        "  a log y axis without a range draws its values <= 0 on a grey band labelled 0 below a break\n"
        "\n"
        "Example:\n"
        "  vri-plot experiments/plots/paper-b-speed-bonsai.yaml -o results/paper-b-cpu/speed-bonsai.png\n"
        "      writes speed-bonsai.png, .svg and .gp; a malformed spec is one line FILE:LINE:COL: what\n"
        "  vri-plot experiments/plots/paper-b-speed-bonsai.yaml --data-dir build/experiments-quick/paper-b-cpu \\\n"
        "      -o speed-bonsai-quick.png       the same figure of another results folder's data");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    const vri::PlotSpec spec = vri::loadPlotSpec(specPath, dataDir);
    for (const std::string& warning : spec.warnings) std::cerr << kTool << ": warning: " << vri::printable(warning) << '\n';
    std::vector<vri::InputArgument> inputs{{"SPEC", specPath}};
    for (const vri::PlotPanel& panel : spec.panels)
        for (const vri::PlotSeries& series : panel.series) inputs.push_back({"SPEC's data file", series.file.string()});
    std::vector<vri::OutputArgument> outputs{{"-o's script", std::filesystem::path(output).replace_extension(".gp").string()}};
    if (!scriptOnly) {
        outputs.push_back({"-o", output});
        outputs.push_back({"-o's SVG", std::filesystem::path(output).replace_extension(".svg").string()});
    }
    vri::requireOutputsApartFromInputs(outputs, inputs);
    if (scriptOnly) vri::writePlotScript(spec, output);
    else vri::drawPlot(spec, output);
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
