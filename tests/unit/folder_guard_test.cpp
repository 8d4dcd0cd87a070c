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
