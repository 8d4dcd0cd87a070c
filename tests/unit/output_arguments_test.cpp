#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "temp_dir.h"
#include "common/cli.h"
#include "libvri/util/same_file.h"

using namespace vri;
namespace fs = std::filesystem;

namespace {

// The UsageError a check throws, or "no error".
template <class Check>
std::string usageError(Check&& check) {
    try {
        check();
    } catch (const UsageError& e) {
        return e.what();
    }
    return "no error";
}

std::string distinctError(const std::vector<OutputArgument>& outputs) {
    return usageError([&] { requireDistinctOutputs(outputs); });
}

std::string apartError(const std::vector<OutputArgument>& outputs, const std::vector<InputArgument>& inputs) {
    return usageError([&] { requireOutputsApartFromInputs(outputs, inputs); });
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
    CHECK(distinctError({{"-o", "a.exr"}, {"--stats", "-"}}) == "no error");                // standard output, once
    // Twice, the two would run into each other on it.
    CHECK(distinctError({{"--stats", "-"}, {"--log", "-"}}) == "--log: '-' (standard output) is also --stats's output");
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

TEST_CASE("same file: by device and inode, through links and spellings; a missing path is no file") {
    test::TempDir dir("same");
    const fs::path a = dir / "a.txt", b = dir / "b.txt";
    std::ofstream(a) << "a";
    std::ofstream(b) << "b";
    CHECK(sameExistingFile(a, a));
    CHECK(!sameExistingFile(a, b));
    fs::create_symlink(a, dir / "sym.txt");
    fs::create_hard_link(a, dir / "hard.txt");
    fs::create_directory(dir / "sub");
    CHECK(sameExistingFile(dir / "sym.txt", a));
    CHECK(sameExistingFile(a, dir / "hard.txt"));
    CHECK(sameExistingFile(dir / "sub" / ".." / "a.txt", a));
    CHECK(!sameExistingFile(dir / "missing.txt", dir / "missing.txt"));  // nothing to replace yet
    fs::create_symlink(dir / "missing.txt", dir / "dangling.txt");
    CHECK(!sameExistingFile(dir / "dangling.txt", dir / "missing.txt"));
    CHECK(!sameExistingFile(dir.path, dir.path));         // a directory is no output to replace
    CHECK(!sameExistingFile("/dev/null", "/dev/null"));  // nor is a device
}

TEST_CASE("output arguments: an output that is one of the inputs is an error naming both") {
    test::TempDir dir("apart");
    const std::string tf = (dir / "tf.yaml").string(), out = (dir / "out.csv").string();
    std::ofstream(tf) << "points: []\n";
    CHECK(apartError({{"-o", out}}, {{"TF", tf}}) == "no error");  // does not exist yet
    std::ofstream(out) << "s\n";
    CHECK(apartError({{"-o", out}, {"--csv", ""}, {"--json", "-"}}, {{"TF", tf}, {"B", ""}, {"A", "-"}}) == "no error");
    CHECK(apartError({{"-o", tf}}, {{"TF", tf}}) == "-o '" + tf + "' is the same file as TF '" + tf + "'");
    fs::create_symlink(tf, dir / "link.yaml");
    fs::create_hard_link(tf, dir / "hard.yaml");
    const std::string link = (dir / "link.yaml").string(), hard = (dir / "hard.yaml").string();
    CHECK(apartError({{"-o", out}, {"--stats", link}}, {{"--volume", out + ".x"}, {"--tf", tf}}) ==
          "--stats '" + link + "' is the same file as --tf '" + tf + "'");
    CHECK(apartError({{"-o", hard}}, {{"TF", tf}}) == "-o '" + hard + "' is the same file as TF '" + tf + "'");
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path);
    CHECK(apartError({{"-o", "tf.yaml"}}, {{"TF", tf}}) == "-o 'tf.yaml' is the same file as TF '" + tf + "'");
    fs::current_path(cwd);
}

TEST_CASE("volume inputs: a header comes with the data file it names") {
    test::TempDir dir("volume-inputs");
    std::ofstream(dir / "v.raw") << std::string(8, '\0');
    std::ofstream(dir / "v.nhdr") << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"
                                     "data file: v.raw\n";
    std::ofstream(dir / "v.mhd") << "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = v.raw\n";
    std::ofstream(dir / "v.dat") << "Rawfile: v.raw\nResolution: 2 2 2\nFormat: UINT8\n";
    std::ofstream(dir / "local.mha") << "NDims = 3\nElementDataFile = LOCAL\n";
    std::ofstream(dir / "broken.nhdr") << "not a header\n";
    const std::string raw = (dir / "v.raw").string();
    for (const char* header : {"v.nhdr", "v.mhd", "v.dat"}) {
        INFO(header);
        const std::vector<InputArgument> inputs = volumeInputArguments("--volume", (dir / header).string());
        REQUIRE(inputs.size() == 2);
        CHECK(inputs[0].option == "--volume");
        CHECK(inputs[1].option == "--volume's data file");
        CHECK(inputs[1].path == raw);
        CHECK(apartError({{"output's raw file", raw}}, inputs) ==
              "output's raw file '" + raw + "' is the same file as --volume's data file '" + raw + "'");
    }
    CHECK(volumeInputArguments("input", (dir / "local.mha").string()).size() == 1);
    CHECK(volumeInputArguments("input", (dir / "broken.nhdr").string()).size() == 1);  // reading it says why
    CHECK(volumeInputArguments("input", raw).size() == 1);
    CHECK(volumeInputArguments("--volume", "").empty());
}
