// vri-tf: a transfer function as a table, for plotting it beside the images it made.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/core/transfer_function.h"
#include "libvri/io/transfer_function_yaml.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/csv.h"
#include "libvri/util/format.h"

namespace {

constexpr const char* kTool = "vri-tf";

std::string row(double s, double r, double g, double b, double tau) {
    return vri::csvLine({vri::exactNumber(s), vri::exactNumber(r), vri::exactNumber(g), vri::exactNumber(b),
                         vri::exactNumber(tau), vri::exactNumber(1.0 - std::exp(-tau))});
}

// Rows at `samples` evenly spaced s over [0, 1], and at every breakpoint in [0, 1] with the
// breakpoint's own values: a jump (points of equal s) keeps both sides, so a line through the rows
// draws the function exactly. A sample that falls on a breakpoint is left to the breakpoint's rows.
std::string tabulate(const vri::TransferFunction& tf, int samples) {
    std::string csv = vri::csvLine({"s", "r", "g", "b", "tau", "alpha_per_voxel"});
    const auto& points = tf.points();
    std::size_t next = 0;
    for (int i = 0; i < samples; ++i) {
        const double s = static_cast<double>(i) / (samples - 1);
        bool onBreakpoint = false;
        for (; next < points.size() && points[next].s <= s; ++next) {
            const vri::TransferFunctionPoint& p = points[next];
            if (p.s < 0.0) continue;
            csv += row(p.s, p.r, p.g, p.b, p.tau);
            onBreakpoint = p.s == s;
        }
        if (!onBreakpoint) {
            const vri::TransferFunctionSample<double> v = tf(s);
            csv += row(s, v.r, v.g, v.b, v.tau);
        }
    }
    return csv;
}

// --check: what the file holds, in one line, and the warnings a first transfer function needs: a
// function that shows nothing, or whose points leave part of s in [0, 1] to the end points' values.
int check(const std::string& path, const vri::TransferFunction& tf) {
    const auto& points = tf.points();
    const vri::TransferFunctionSample<double> top = tf.largest();
    const double tauMax = top.tau, colourMax = std::max({top.r, top.g, top.b});
    std::cout << path << ": " << points.size() << " points, s from " << vri::exactNumber(points.front().s) << " to "
              << vri::exactNumber(points.back().s) << ", emission " << vri::emissionModelName(tf.emission())
              << ", largest tau " << vri::exactNumber(tauMax) << ", largest colour " << vri::exactNumber(colourMax)
              << "\n";
    if (tauMax == 0) std::cerr << kTool << ": warning: " << path << ": every tau is 0: the volume is invisible\n";
    else if (colourMax == 0) std::cerr << kTool << ": warning: " << path << ": every colour is 0: the image is black\n";
    if (points.front().s > 0 || points.back().s < 1)
        std::cerr << kTool << ": warning: " << path << ": the points cover s from " << vri::exactNumber(points.front().s)
                  << " to " << vri::exactNumber(points.back().s)
                  << "; below and above, s takes the first and the last point's value\n";
    return vri::kExitOk;
}

int run(int argc, char** argv) {
    std::string tfPath, output;
    int samples = 512;
    bool checkOnly = false;

    CLI::App app{"Tabulates a transfer function: CSV with columns s, r, g, b, tau and alpha_per_voxel = 1 - exp(-tau) "
                 "(the opacity of one world unit, one voxel at unit spacing), at evenly spaced s over [0, 1] and at "
                 "every breakpoint, both sides of a jump included.",
                 kTool};
    app.add_option("TF,--tf", tfPath, "transfer function YAML (positional, or --tf as in experiment commands)")->required();
    app.add_option("--samples", samples, "evenly spaced s over [0, 1], ends included (breakpoints come on top)")
        ->check(vri::integerRange(2, 1000000))
        ->capture_default_str();
    app.add_option("-o,--output", output, "CSV file; '-' writes to stdout");
    app.add_flag("--check", checkOnly,
                 "read and check the file only: one line on stdout with what it holds, warnings on stderr for a "
                 "function that shows nothing or leaves part of [0, 1] to its end points")
        ->excludes("--output");
    app.footer("Examples:\n"
               "  vri-tf experiments/tf/paper-b-bonsai.yaml -o tf-bonsai.csv\n"
               "  vri-tf experiments/tf/paper-b-bluntfin.yaml --samples 64 -o - | column -ts,\n"
               "  vri-tf --check my-tf.yaml      # after writing one: its points, range and emission, or what is wrong\n"
               "  vri-tf experiments/tf/paper-b-engine.yaml -o tf-engine.csv && \\\n"
               "      vri-plot experiments/plots/paper-b-tf-engine.yaml --data-dir . -o tf-engine.png\n"
               "\n"
               "The file's format: experiments/README.md, \"Transfer functions\". "
               "A bad transfer function (unsorted points, a negative value) is one error line naming the file; "
               "exit 0 on success, 1 on a bad or missing file, non-zero on a bad argument. The CSV is written "
               "atomically.");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    if (checkOnly) return check(tfPath, vri::loadTransferFunction(tfPath));
    if (output.empty()) throw vri::UsageError("--output is required (or --check)");
    vri::requireOutputsApartFromInputs({{"-o", output}}, {{"TF", tfPath}});
    vri::writeTextFile(output, tabulate(vri::loadTransferFunction(tfPath), samples));
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
