// Running gnuplot on a figure's script, with every output written atomically.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "vri/atomic_file.h"
#include "vri/error.h"
#include "vri/plot.h"
#include "vri/provenance.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

void requirePngPath(const fs::path& png) {
    if (png.extension() != ".png") throw Error(png.string() + ": the figure's name must end in .png");
}

fs::path besidePng(const fs::path& png, const char* extension) {
    return fs::path(png).replace_extension(extension);
}

}  // namespace

void writePlotScript(const PlotSpec& spec, const fs::path& png) {
    requirePngPath(png);
    const fs::path script = besidePng(png, ".gp");
    writeTextFile(script, gnuplotScript(spec, script, png.filename().string(), besidePng(png, ".svg").filename().string()));
}

void drawPlot(const PlotSpec& spec, const fs::path& png) {
    requirePngPath(png);
    if (!commandAvailable("gnuplot"))
        throw Error("gnuplot is not installed (Debian: apt-get install gnuplot-nox); nothing was written");
    const fs::path script = besidePng(png, ".gp"), svg = besidePng(png, ".svg");
    const std::string text = gnuplotScript(spec, script, png.filename().string(), svg.filename().string());
    // Nested, so that the three files appear only once gnuplot has drawn both images.
    writeAtomically(script, [&](const fs::path& tmpScript) {
        std::ofstream(tmpScript) << text;
        writeAtomically(png, [&](const fs::path& tmpPng) {
            writeAtomically(svg, [&](const fs::path& tmpSvg) {
                const fs::path log = fs::path(tmpScript).replace_extension(".log");
                const std::string command = "gnuplot -e " +
                                            shellQuote("png_out='" + fs::absolute(tmpPng).string() + "'; svg_out='" +
                                                       fs::absolute(tmpSvg).string() + "'") +
                                            " " + shellQuote(tmpScript.string()) + " 2>" + shellQuote(log.string());
                const int rc = std::system(command.c_str());
                std::ifstream messages(log);
                std::ostringstream warnings;
                warnings << messages.rdbuf();
                std::error_code ignored;
                fs::remove(log, ignored);
                if (rc != 0 || !fs::is_regular_file(tmpPng) || !fs::is_regular_file(tmpSvg)) {
                    std::string reason = warnings.str();
                    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
                    reason = reason.substr(reason.find_last_of('\n') + 1);
                    throw Error(png.string() + ": gnuplot failed" + (reason.empty() ? "" : ": " + reason));
                }
                if (!warnings.str().empty()) std::fputs(warnings.str().c_str(), stderr);
            });
        });
    });
}

}  // namespace vri
