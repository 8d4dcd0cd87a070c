#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.h"
#include "common/cli.h"

using namespace vri;
namespace fs = std::filesystem;

namespace {

std::string distinctError(const std::vector<OutputArgument>& outputs) {
    try {
        requireDistinctOutputs(outputs);
    } catch (const UsageError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST_CASE("output arguments: the image must be an .exr file") {
    CHECK_NOTHROW(requireExrOutput({"-o", "a.exr"}));
    CHECK_NOTHROW(requireExrOutput({"-o", "dir.v2/A.EXR"}));
    CHECK_THROWS_WITH_AS(requireExrOutput({"-o", "x.png"}), doctest::Contains("-o: 'x.png' is not an .exr file"),
                         UsageError);
    CHECK_THROWS_AS(requireExrOutput({"-o", "exr"}), UsageError);
    CHECK_THROWS_AS(requireExrOutput({"-o", "a.exr.tmp"}), UsageError);
}

TEST_CASE("output arguments: one file named twice, however spelled, is an error") {
    test::TempDir dir("outputs");
    const std::string x = (dir / "x.png").string();
    CHECK(distinctError({{"-o", "a.exr"}, {"--png", "a.png"}, {"--stats", "a.json"}}) == "no error");
    CHECK(distinctError({{"-o", "a.exr"}, {"--png", ""}, {"--stats", ""}}) == "no error");  // not asked for
    CHECK(distinctError({{"--stats", "-"}, {"--log", "-"}}) == "no error");                 // standard output
    CHECK(distinctError({{"-o", x}, {"--png", x}}) == "--png: '" + x + "' is also -o's output");
    CHECK(distinctError({{"-o", x}, {"--stats", (dir / "sub" / ".." / "." / "x.png").string()}})
              .starts_with("--stats: "));
    fs::create_directory(dir / "sub");
    CHECK(distinctError({{"-o", x}, {"--stats", (dir / "sub" / ".." / "x.png").string()}}).ends_with("-o's output"));
    // A symbolic link to the file, and a hard link (two names of one inode).
    std::ofstream(x) << "x";
    fs::create_symlink(x, dir / "link.png");
    CHECK(distinctError({{"-o", x}, {"--png", (dir / "link.png").string()}}).ends_with("-o's output"));
    fs::create_hard_link(x, dir / "hard.png");
    CHECK(distinctError({{"-o", x}, {"--png", (dir / "hard.png").string()}}).ends_with("-o's output"));
    // A relative spelling of an absolute path.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path);
    CHECK(distinctError({{"-o", "x.png"}, {"--png", x}}).ends_with("-o's output"));
    fs::current_path(cwd);
}
