// Renders paper A's analytic field with vri::core and writes the float RGBA image with vri::io: the
// image `vri-render --field linear --tf experiments/tf/paper-a-linear.yaml --size 64x48 -o FILE` makes,
// bit for bit (tests/tools/install.sh checks it), from a program built against the installed package.
#include <exception>
#include <iostream>

#include "libvri/core/cpu_renderer.h"
#include "libvri/io/image_io.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: render_linear_field OUTPUT.exr\n";
        return 64;
    }
    try {
        // Paper A's field: f = (x + 1.5) / 3 across the 3-unit cube centred at the origin, standing for a
        // 5^3 grid; emission g(s) = s and extinction tau(s) = s / 2 (experiments/tf/paper-a-linear.yaml).
        const vri::TransferFunction tf({{0.0, 0.0, 0.0, 0.0, 0.0}, {1.0, 1.0, 1.0, 1.0, 0.5}},
                                       vri::EmissionModel::Colour);
        const vri::Scene scene{nullptr, vri::LinearField{}, vri::GridConvention::CellCentred, tf};
        // Looking at the cube along -z from just far enough to see all of it, 30 degrees vertically.
        const vri::Camera camera(vri::framingCamera(scene.box(), 64, 48, 30.0));
        vri::RenderOptions options;  // paper A's Riemann sum, Entry Align, two samples per voxel, double
        vri::writeExr(argv[1], vri::render(scene, camera, options));
    } catch (const std::exception& e) {
        std::cerr << "render_linear_field: error: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
