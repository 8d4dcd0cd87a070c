// What vri-run does to an experiment folder before it works there: lock it, clear dead writers' temp files.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "temp_dir.h"
#include "libvri/util/error.h"
#include "libvri/util/folder_lock.h"
#include "libvri/util/process.h"
#include "libvri/util/stale_temp_files.h"
#include "libvri/util/utf8.h"

namespace fs = std::filesystem;

namespace {

// A pid that no process has now: a child that has been reaped.
pid_t deadPid() {
    const auto program = vri::findProgram("true");
    REQUIRE(program);
    const pid_t pid = vri::startProcess(*program, {"true"});
    vri::waitProcess(pid);
    return pid;
}

}  // namespace

TEST_CASE("folder lock: one holder at a time, named to the second") {
    vri::test::TempDir dir("lock");
    {
        const vri::FolderLock first(dir / "exp");
        std::string pid;
        std::ifstream(dir / "exp" / vri::kFolderLockName) >> pid;
        CHECK(pid == std::to_string(::getpid()));
        // flock locks an open file: a second open, even in this process, is refused.
        const std::string holder = "in use by another vri-run (pid " + std::to_string(::getpid()) + ": ";
        CHECK_THROWS_WITH_AS(vri::FolderLock(dir / "exp"), doctest::Contains(holder.c_str()), vri::Error);
    }
    const vri::FolderLock again(dir / "exp");  // released with its holder
    fs::create_directories(dir / "link");
    fs::create_symlink(dir / "elsewhere", dir / "link" / vri::kFolderLockName);
    CHECK_THROWS_WITH_AS(vri::FolderLock(dir / "link"), doctest::Contains("cannot open the lock file"), vri::Error);
}

TEST_CASE("stale temp files: a dead writer's of the target are removed; a live one's, look-alikes and all else kept") {
    vri::test::TempDir dir("stale");
    const std::string dead = std::to_string(deadPid()), live = std::to_string(::getpid());
    CHECK(vri::temporaryFileFor(dir / "a.exr", 42) == dir / ".a.tmp.42.exr");
    CHECK(vri::temporaryFileFor("fig", 7) == ".fig.tmp.7");
    const std::vector<std::string> stale = {".a.tmp." + dead + ".exr"};
    const std::vector<std::string> kept = {".a.tmp." + live + ".exr",        // its writer is at work
                                           "a.tmp." + dead + ".exr",         // not hidden
                                           ".a.tmp." + dead,                 // another target's (a)
                                           ".a.tmp." + dead + ".exr.bak",    // a user's copy
                                           ".a.tmp." + dead + ".png",        // another target's (a.png)
                                           ".a.tmp.0" + dead + ".exr",       // no pid prints a leading zero
                                           ".a.tmp.+" + dead + ".exr",
                                           ".a.tmp.x" + dead + ".exr",
                                           ".a.tmp..exr",
                                           ".notes.tmp." + dead + ".txt",    // a look-alike of another name
                                           ".b.a.tmp." + dead + ".exr",
                                           "a.exr"};
    for (const auto& name : stale)
        std::ofstream(dir / name) << "x";
    for (const auto& name : kept)
        std::ofstream(dir / name) << "x";
    fs::create_directories(dir / "d" / (".a.tmp." + dead + ".exr"));  // not a file
    fs::create_directories(dir / "l");
    fs::create_symlink(dir / "a.exr", dir / "l" / (".a.tmp." + dead + ".exr"));  // not a regular file

    CHECK(vri::removeStaleTempFiles(dir / "a.exr") == std::vector<fs::path>{dir / stale[0]});
    for (const auto& name : kept) {
        INFO(name);
        CHECK(fs::exists(dir / name));
    }
    CHECK(vri::removeStaleTempFiles(dir / "d" / "a.exr").empty());
    CHECK(fs::is_directory(dir / "d" / (".a.tmp." + dead + ".exr")));
    CHECK(vri::removeStaleTempFiles(dir / "l" / "a.exr").empty());
    CHECK(fs::is_symlink(dir / "l" / (".a.tmp." + dead + ".exr")));
    CHECK(vri::removeStaleTempFiles(dir / "no-such-folder" / "a.exr").empty());
}

TEST_CASE("stale temp files: a target name of 240 to 255 bytes gets a temporary name within 255 bytes") {
    vri::test::TempDir dir("long");
    const std::string dead = std::to_string(deadPid());
    for (const std::size_t length : {239u, 240u, 250u, 255u}) {
        CAPTURE(length);
        const std::string name = std::string(length - 4, 'a') + ".exr";
        const fs::path tmp = vri::temporaryFileFor(dir / name, 2147483647);  // the most digits a pid has
        CHECK(tmp.filename().string().size() <= 255u);
        CHECK(tmp.extension() == ".exr");
        CHECK(tmp.parent_path() == dir.path);
        // A file of that name can be made, and a dead writer's is found again by the target's name.
        const fs::path stale = vri::temporaryFileFor(dir / name, std::stoi(dead));
        std::ofstream(stale) << "x";
        REQUIRE(fs::exists(stale));
        CHECK(vri::removeStaleTempFiles(dir / name) == std::vector<fs::path>{stale});
    }
    // Two long names alike but for their ends keep apart; a short one keeps its plain name.
    const std::string stem(248, 'b');
    CHECK(vri::temporaryFileFor(stem + "1.exr", 7) != vri::temporaryFileFor(stem + "2.exr", 7));
    CHECK(vri::temporaryFileFor(std::string(234, 'c') + ".exr", 7).filename().string() ==
          "." + std::string(234, 'c') + ".tmp.7.exr");
    // The cut falls between characters: a stem of two-byte UTF-8 characters stays valid UTF-8.
    std::string accents;
    while (accents.size() < 250) accents += "\xc3\xa9";
    const std::string cut = vri::temporaryFileFor(accents + ".csv", 7).filename().string();
    CHECK(cut.size() <= 255u);
    CHECK_FALSE(vri::firstInvalidUtf8(cut).has_value());
    // An extension too long to leave room is dropped.
    const fs::path noExtension = vri::temporaryFileFor("a." + std::string(250, 'x'), 7);
    CHECK(noExtension.filename().string().size() <= 255u);
    CHECK(noExtension.filename().string().ends_with(".tmp.7"));
}

TEST_CASE("utf8: well-formed sequences pass, the first byte of an ill-formed one is found and escaped") {
    CHECK_FALSE(vri::firstInvalidUtf8("plain.exr").has_value());
    CHECK_FALSE(vri::firstInvalidUtf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80").has_value());
    CHECK(vri::firstInvalidUtf8("bad\xff.exr") == 3u);
    CHECK(vri::firstInvalidUtf8("\xc0\xaf") == 0u);          // overlong '/'
    CHECK(vri::firstInvalidUtf8("x\xed\xa0\x80") == 1u);     // a surrogate
    CHECK(vri::firstInvalidUtf8("\xf4\x90\x80\x80") == 0u);  // past U+10FFFF
    CHECK(vri::firstInvalidUtf8("ab\xc3") == 2u);            // cut short
    CHECK(vri::escapeInvalidUtf8("bad\xff\xc3\xa9.exr") == "bad\\xFF\xc3\xa9.exr");
}
