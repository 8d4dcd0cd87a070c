#pragma once
// The command lines of the tools that take a scene and the render option table (render_option_table.h):
// vri-render and vri-reference (RenderJob, render_job.h), vri-outside (an outside renderer on the scene
// card, outside_renderer.h) and vri-verify (verification.h). This file reads and checks options and
// writes files; the work is the render layer's. A tool's main() calls its function in render_main.h, in the
// spirit of GDAL's GDALTranslate(..., GDALTranslateOptionsNew(argv)).
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/frame_timing.h"
#include "common/preview_options.h"
#include "common/render_main.h"
#include "common/scene_options.h"
#include "libvri/core/render_option_table.h"

namespace vri {

class RenderCommand {
public:
    // Parses the command line. --help, --list-devices and usage errors end the command here: run()
    // then returns their exit code without rendering.
    static RenderCommand fromArgs(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv) {
        return RenderCommand(tool, help, argc, argv, Mode::Vri);
    }
    // vri-outside: vri-render's scene and method options describe the scene card an outside renderer's
    // command (after --) renders; its image and stats become the run's (outside_renderer.h).
    static RenderCommand outsideFromArgs(const RenderCommandHelp& help, int argc, char** argv) {
        return RenderCommand(RenderTool::Render, help, argc, argv, Mode::Outside);
    }
    // vri-verify: the same options describe the cards of a sweep of steps; the report (verification.h).
    static RenderCommand verifyFromArgs(const RenderCommandHelp& help, int argc, char** argv) {
        return RenderCommand(RenderTool::Render, help, argc, argv, Mode::Verify);
    }
    RenderCommand(const RenderCommand&) = delete;
    RenderCommand& operator=(const RenderCommand&) = delete;

    // Checks every option, renders, checks the image and writes the outputs; the exit code (cli.h).
    int run();

private:
    enum class Mode { Vri, Outside, Verify };  // vri's own render (or card), an outside renderer's run, a report
    RenderCommand(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv, Mode mode);
    // The values of the table's options, applied in table order and checked against each other.
    RenderRequest request() const;
    // Whether `option` is one of this tool's and was given.
    bool given(const std::string& option) const;
    // --describe: the scene card (and the voxels), no render.
    int describe();
    // vri-outside, vri-verify: the command after -- and --renderer-image, checked (usage errors).
    void requireRendererCommand() const;
    // vri-outside: the card, the renderer's run, the run's image and record.
    int runOutside();
    // vri-verify: the sweep, the report and its exit code.
    int runVerify();

    struct TableOption {
        const RenderOptionRow* row;
        CLI::Option* option;
    };

    RenderTool tool_;
    std::string name_;  // "vri-render", "vri-reference"
    int argc_;
    char** argv_;
    CLI::App app_;
    std::vector<TableOption> tableOptions_;
    // Where CLI11 converts the table's values (which refuses what is not a number); the text given is
    // what the rows read, from the options' results.
    std::vector<std::variant<double, int, std::string, bool>> slots_;
    SceneOptions scene_;
    FrameTiming timing_;
    PreviewOptions preview_;
    std::string output_, pngPath_, statsPath_, logPath_, errorImagePath_, describePath_, voxelsPath_;
    bool quiet_ = false, allowNonFinite_ = false;
    Mode mode_ = Mode::Vri;
    bool keepWork_ = false, exitZero_ = false;
    std::vector<std::string> rendererCommand_;  // vri-outside, vri-verify: after --
    std::string rendererImage_ = "exr", rendererName_;
    std::string steps_ = "2,1,0.5,0.25,0.125", reportPath_, jsonPath_, junitPath_;  // vri-verify
    double minOrder_ = 0.75, referenceTolerance_ = 1e-9, timeout_ = 0.0;
    int seeds_ = 1, rendererJobs_ = 1;  // vri-verify --seeds, --renderer-jobs
    std::optional<int> exitCode_;  // set when parsing ended the command
};

}  // namespace vri
