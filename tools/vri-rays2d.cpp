// vri-rays2d: paper A's 2D analytic study: a fan of rays through a rotated square, the closed form
// of the volume rendering integral per ray against the discrete sum of each sample placement.
#include <CLI/CLI.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/cli.h"
#include "libvri/report/rays2d_report.h"
#include "libvri/util/atomic_file.h"

namespace {

constexpr const char* kTool = "vri-rays2d";

int run(int argc, char** argv) {
    vri::Study2D study;
    std::string convention = "node", eye = "-9,0", rates = "1,4,16";
    std::string placements = "eye,entry,entry-exit,entry-exit-corner";
    double rotationDegrees = 180.0 / 7.0, diagramRate = 1.0;
    std::string output, errors, errorsCsv, convergence, diagram, diagramRays = "20,45,70,95,103,105", fieldImage;
    int fieldResolution = 121;

    CLI::App app{"Paper A's 2D study (Sec. V-A): casts a fan of rays from an eye through a rotated square holding "
                 "f(x, y) = (x + 1.5) / 3 on a grid, g(s) = s, tau(s) = s / 2, I0 = 0, and writes per ray the "
                 "closed form of the volume rendering integral and the Riemann sum of eq. (6) for each sample "
                 "placement and sampling rate.",
                 kTool};
    app.add_option("--convention", convention, "grid convention: node (paper A) or cell (clamped at the border)")
        ->capture_default_str();
    app.add_option("--rays", study.rays, "rays in the fan")->capture_default_str();
    app.add_option("--fov", study.fovDegrees, "field of view, degrees; ray i at -fov/2 + (i + 1/2) fov / rays")
        ->capture_default_str();
    app.add_option("--eye", eye, "eye X,Y")->capture_default_str();
    app.add_option("--rotation", rotationDegrees, "the square's rotation about the origin, degrees (pi/7)")
        ->capture_default_str();
    app.add_option("--side", study.side, "the square's side, centred at the origin")->capture_default_str();
    app.add_option("--grid", study.gridSize, "f is discretised on GRIDxGRID voxels")->capture_default_str();
    app.add_option("--placements", placements, "placements, comma separated")->capture_default_str();
    app.add_option("--rates", rates, "sampling rates in samples per voxel, comma separated")->capture_default_str();
    app.add_option("-o,--output", output, "per-ray CSV: ray, angle_deg, length, closed_form, PLACEMENT_rRATE..., "
                                          "n_PLACEMENT_rRATE... (sample counts)");
    app.add_option("--errors", errors, "error table (Markdown): max/mean |error| per placement and rate");
    app.add_option("--errors-csv", errorsCsv, "the same table as CSV");
    app.add_option("--convergence", convergence, "CSV: rate, PLACEMENT_max, PLACEMENT_mean (|error| over the rays)");
    app.add_option("--diagram", diagram, "Fig. 1 data (CSV of segments: panel, kind, x, y, x2, y2)");
    app.add_option("--diagram-rays", diagramRays, "rays drawn in the diagram")->capture_default_str();
    app.add_option("--diagram-rate", diagramRate, "sampling rate of the diagram")->capture_default_str();
    app.add_option("--field-image", fieldImage, "Fig. 3 data (CSV: x, y, analytic, reconstructed over the square)");
    app.add_option("--field-resolution", fieldResolution, "points per side of the field image")->capture_default_str();
    app.footer("Examples:\n"
               "  vri-rays2d -o rays.csv --errors errors.md            # paper A's setup, rates 1, 4, 16\n"
               "  vri-rays2d --convention cell --rates 1,2,4,8,16,32 -o cell.csv\n"
               "  vri-rays2d --diagram fig1.csv --field-image fig3.csv\n"
               "\n"
               "The closed form is exact for the grid as stored: f is linear along a ray between the lines "
               "through the voxel samples (and clamped beyond the outermost ones in the cell convention), so "
               "each piece is integrated exactly. Every output is written atomically.\n"
               "Limits: at most 1e6 rays; 1e9 samples over the fan (rays x placements x the sum of the rates x "
               "the voxels a ray crosses); 1e6 samples in the diagram; 2048x2048 points in the field image.");
    if (auto exitCode = vri::parseArguments(app, kTool, argc, argv)) return *exitCode;

    const bool fanWanted = !output.empty() || !errors.empty() || !errorsCsv.empty() || !convergence.empty();
    if (!fanWanted && diagram.empty() && fieldImage.empty())
        throw vri::Error("nothing to write: give -o, --errors, --errors-csv, --convergence, --diagram or --field-image");
    vri::requireDistinctOutputs({{"-o", output},
                                 {"--errors", errors},
                                 {"--errors-csv", errorsCsv},
                                 {"--convergence", convergence},
                                 {"--diagram", diagram},
                                 {"--field-image", fieldImage}});
    study.convention = vri::parseGridConvention(convention, "--convention");
    study.eye = vri::parseVec2(eye, "--eye");
    if (!std::isfinite(rotationDegrees)) throw vri::Error("--rotation: expected a finite angle in degrees");
    study.rotationRadians = rotationDegrees * std::numbers::pi / 180.0;
    if (!(diagramRate > 0.0)) throw vri::Error("--diagram-rate: expected a positive sampling rate");
    std::vector<vri::Placement> chosen;
    for (const std::string& name : vri::parseWordList(placements, "--placements")) chosen.push_back(vri::parsePlacement(name, "--placements"));
    const std::vector<double> sampleRates = vri::parsePositiveList(rates, "--rates");
    const vri::Rays2D rays2d(study);  // validates the study
    const std::vector<int> drawn =
        diagram.empty() ? std::vector<int>{} : vri::parseIndexList(diagramRays, "--diagram-rays", study.rays);

    vri::OutputSet outputs;
    if (fanWanted) {
        const vri::Fan fan = vri::castFan(rays2d, chosen, sampleRates);
        if (!output.empty()) outputs.add(output, vri::fanCsv(fan));
        vri::Table table = vri::fanErrorTable(fan);
        // Two such tables often sit one under the other (node and cell): the title starts with its grid.
        table.title = (study.convention == vri::GridConvention::NodeCentred
                           ? "Node-centred grid (voxel i at i / (n - 1), paper A's). "
                           : "Cell-centred grid (voxel i at (i + 1/2) / n, clamped at the border). ") +
                      table.title;
        if (!errors.empty()) outputs.add(errors, vri::toMarkdown(table));
        if (!errorsCsv.empty()) outputs.add(errorsCsv, vri::toCsv(table));
        if (!convergence.empty()) outputs.add(convergence, vri::convergenceCsv(fan));
    }
    if (!diagram.empty()) outputs.add(diagram, vri::diagramCsv(rays2d, drawn, chosen, diagramRate));
    if (!fieldImage.empty()) outputs.add(fieldImage, vri::fieldCsv(rays2d, fieldResolution));
    outputs.write();
    return vri::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
    return vri::guardedMain(kTool, [&] { return run(argc, argv); });
}
