#pragma once
// The mains of the tools that take a scene and the render option table: each parses its command line, runs
// and returns its exit code (cli.h); RenderCommand (render_command.h) does the work. Apart from that
// header, so that a tool's main does not compile CLI11 again (some 5 s of each of the four tools' build).
#include <string_view>

#include "libvri/core/render_option_table.h"

namespace vri {

// What --help says about a tool beyond its options.
struct RenderCommandHelp {
    std::string_view description;
    std::string_view footer;  // examples and notes
};

// vri-render (RenderTool::Render) and vri-reference (RenderTool::Reference).
int renderMain(RenderTool tool, const RenderCommandHelp& help, int argc, char** argv);
// vri-outside: an outside renderer's run on the scene card.
int outsideMain(const RenderCommandHelp& help, int argc, char** argv);
// vri-verify: the report on an outside renderer.
int verifyMain(const RenderCommandHelp& help, int argc, char** argv);

}  // namespace vri
