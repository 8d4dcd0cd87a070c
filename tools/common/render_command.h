#pragma once
// vri-render and vri-reference, whole: the command line read off the render option table
// (render_option_table.h) plus the scene, timing, preview and output options, then the render, its
// checks and its files. A tool's main() is
//     return vri::RenderCommand::fromArgs(vri::RenderTool::Render, help, argc, argv).run();
// in the spirit of GDAL's GDALTranslate(..., GDALTranslateOptionsNew(argv)).
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/frame_timing.h"
#include "common/nonfinite_option.h"
#include "common/preview_options.h"
#include "common/scene_options.h"
#include "libvri/core/render_option_table.h"

namespace vri {

// What --help says about a tool beyond its options.
struct RenderCommandHelp {
    std::string_view description;
    std::string_view footer;  // examples and notes
};

class RenderCommand {
public:
    // Parses the command line. --help, --list-devices and usage errors end the command here: run()
    // then returns their exit code without rendering.
    static RenderCommand fromArgs(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv) {
        return RenderCommand(tool, help, argc, argv);
    }
    RenderCommand(const RenderCommand&) = delete;
    RenderCommand& operator=(const RenderCommand&) = delete;

    // Checks every option, renders, checks the image and writes the outputs; the exit code (cli.h).
    int run();

private:
    RenderCommand(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv);
    // The values of the table's options, applied in table order and checked against each other.
    RenderRequest request() const;

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
    NonFiniteOption nonfinite_;
    std::string output_, pngPath_, statsPath_, logPath_, errorImagePath_;
    bool quiet_ = false;
    std::optional<int> exitCode_;  // set when parsing ended the command
};

}  // namespace vri
