// vri-plot: a figure (PNG + SVG) drawn by gnuplot from a YAML spec and CSV data, with the
// generated gnuplot script kept beside it.
#include <CLI/CLI.hpp>

#include <string>

#include "vri/cli.h"
#include "vri/plot.h"

namespace {

constexpr const char* kTool = "vri-plot";

int run(int argc, char** argv) {
    std::string specPath, output;
    bool scriptOnly = false;
    CLI::App app{"Draws a figure with gnuplot from a YAML spec that names CSV files and columns: writes FIG.png, "
                 "FIG.svg and FIG.gp, the gnuplot script, so that `gnuplot FIG.gp` redraws it by hand.",
                 kTool};
    app.add_option("SPEC", specPath, "figure spec (YAML)")->required();
    app.add_option("-o,--output", output, "the figure, FIG.png (FIG.svg and FIG.gp are written beside it)")->required();
    app.add_flag("--script-only", scriptOnly, "write FIG.gp only (no gnuplot needed)");
    app.footer(
        "Spec (relative data paths start at the spec's folder):\n"
        "  title: Time against error, Bonsai     # optional\n"
        "  size: [1200, 900]                     # optional, pixels\n"
        "  grid: [2, 2]                          # optional, panel rows x columns\n"
        "  panels:                               # or one panel's keys (x, y, key, pareto, series) at the top\n"
        "    - title: CPU\n"
        "      x: {label: seconds per frame, log: true}\n"
        "      y: {label: max error, log: true, range: [1e-6, 1]}\n"
        "      key: top right                    # top/bottom left/right, outside, off\n"
        "      pareto: true                      # mark points not dominated in (x, y), both minimised\n"
        "      series:\n"
        "        - {file: riemann.csv, x: seconds, y: error, style: linespoints, label: Riemann}\n"
        "        - {file: hist.csv, y: R, style: histogram, label: R}  # vri-diff --histogram bins\n"
        "  styles: line, dashed, dotted, points, linespoints, histogram; color: \"#rrggbb\" (optional)\n"
        "\n"
        "Example:\n"
        "  vri-plot experiments/figs/speed-accuracy.yaml -o results/speed/speed-accuracy.png\n"
        "      writes speed-accuracy.png, .svg and .gp; a malformed spec is one line FILE:LINE:COL: what");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    const vri::PlotSpec spec = vri::loadPlotSpec(specPath);
    if (scriptOnly) vri::writePlotScript(spec, output);
    else vri::drawPlot(spec, output);
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
