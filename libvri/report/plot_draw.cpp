// Running gnuplot on a figure's script, with every output written atomically.
#include <array>
#include <cstdio>

#include "libvri/report/plot.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/file_text.h"
#include "libvri/util/process.h"
#include "libvri/util/stale_temp_files.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

void requirePngPath(const fs::path& png) {
    if (png.extension() != ".png") throw Error(png.string() + ": the figure's name must end in .png");
}

fs::path besidePng(const fs::path& png, const char* extension) { return fs::path(png).replace_extension(extension); }

std::string withoutTrailingBlanks(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r'))
        text.pop_back();
    return text;
}

// What gnuplot drew is only trusted once it reads as a whole image: a PNG from its signature to its
// IEND chunk, an SVG to its closing tag. A full disk or a killed gnuplot leaves less.
std::string incompleteImage(const fs::path& png, const fs::path& svg) {
    static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static constexpr std::array<unsigned char, 12> kEnd = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    const std::string image = tryReadFileText(png).value_or("");
    const auto bytesAre = [&](std::size_t at, const auto& bytes) {
        return image.size() >= at + bytes.size() &&
               std::equal(bytes.begin(), bytes.end(), image.begin() + at,
                          [](unsigned char b, char c) { return b == static_cast<unsigned char>(c); });
    };
    if (image.size() < kSignature.size() + kEnd.size() || !bytesAre(0, kSignature) ||
        !bytesAre(image.size() - kEnd.size(), kEnd))
        return "the PNG it wrote is not a complete PNG (" + std::to_string(image.size()) + " bytes)";
    const std::string drawing = withoutTrailingBlanks(tryReadFileText(svg).value_or(""));
    if (!drawing.starts_with("<?xml") || !drawing.ends_with("</svg>"))
        return "the SVG it wrote is not a complete SVG (" + std::to_string(drawing.size()) + " bytes)";
    return "";
}

// gnuplot's last line of complaint, for a one-line message (guardedMain escapes control characters).
std::string lastLine(const std::string& messages) {
    const std::string trimmed = withoutTrailingBlanks(messages);
    return trimmed.substr(trimmed.find_last_of('\n') + 1);
}

}  // namespace

void writePlotScript(const PlotSpec& spec, const fs::path& png) {
    requirePngPath(png);
    const fs::path script = besidePng(png, ".gp");
    writeTextFile(script,
                  gnuplotScript(spec, script, png.filename().string(), besidePng(png, ".svg").filename().string()));
}

void drawPlot(const PlotSpec& spec, const fs::path& png) {
    requirePngPath(png);
    const auto gnuplot = findProgram("gnuplot");
    if (!gnuplot) throw Error("gnuplot is not installed (Debian: apt-get install gnuplot-nox); nothing was written");
    const fs::path script = besidePng(png, ".gp"), svg = besidePng(png, ".svg");
    const std::string text = gnuplotScript(spec, script, png.filename().string(), svg.filename().string());
    // gnuplot's log is the temporary file of a NAME.log never kept (temporaryFileFor): one a killed run left
    // is removed here, as a rerun removes its images' (vri-run does the same for a figure step).
    removeStaleTempFiles(besidePng(png, ".log"));
    // Nested, so that the three files appear only once gnuplot has drawn both images.
    writeAtomically(script, [&](const fs::path& tmpScript) {
        writeTextFile(tmpScript, text);
        writeAtomically(png, [&](const fs::path& tmpPng) {
            writeAtomically(svg, [&](const fs::path& tmpSvg) {
                const fs::path log = fs::path(tmpScript).replace_extension(".log");
                // The output paths reach the script as ARG1 and ARG2 of `gnuplot -c`: gnuplot never parses
                // them, so no character of a name can be read as gnuplot code.
                const ExitStatus status = runProcess(
                    *gnuplot,
                    {"gnuplot", "-c", tmpScript.string(), fs::absolute(tmpPng).string(), fs::absolute(tmpSvg).string()},
                    {.in = "/dev/null", .out = log, .err = {}, .errToOut = true});
                const std::string messages = tryReadFileText(log).value_or("");
                std::error_code ignored;
                fs::remove(log, ignored);
                std::string reason;
                if (!status.ok())
                    reason = lastLine(messages).empty() ? status.describe() : lastLine(messages);
                else if (!fs::is_regular_file(tmpPng) || !fs::is_regular_file(tmpSvg))
                    reason = "it wrote no PNG or no SVG";
                else
                    reason = incompleteImage(tmpPng, tmpSvg);
                if (!reason.empty()) throw Error(png.string() + ": gnuplot failed: " + reason);
                if (!messages.empty()) std::fputs(messages.c_str(), stderr);
            });
        });
    });
}

}  // namespace vri
