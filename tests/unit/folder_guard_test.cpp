// What vri-run does to an experiment folder before it works there: lock it, clear dead writers' temp files.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
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

TEST_CASE("stale temp files: a dead writer's are removed, a live one's and all else kept") {
    vri::test::TempDir dir("stale");
    const std::string dead = std::to_string(deadPid()), live = std::to_string(::getpid());
    const std::vector<std::string> stale = {".a.tmp." + dead, ".a.tmp." + dead + ".exr", ".b c.tmp." + dead + ".7.png",
                                            "..fig.tmp." + dead + ".tmp." + dead + ".gp"};
    const std::vector<std::string> kept = {".a.tmp." + live + ".exr",
                                           "a.tmp." + dead + ".exr",
                                           ".a.tmp.x" + dead,
                                           ".a.tmp." + dead + "x",
                                           ".tmp." + dead,
                                           ".a.tmp.0.exr",
                                           "manifest.json"};
    for (const auto& name : stale)
        std::ofstream(dir / name) << "x";
    for (const auto& name : kept)
        std::ofstream(dir / name) << "x";
    fs::create_directories(dir / (".d.tmp." + dead));                               // not a file
    fs::create_symlink(dir / "manifest.json", dir / (".l.tmp." + dead + ".json"));  // not a regular file

    auto removed = vri::removeStaleTempFiles(dir.path);
    std::vector<std::string> names;
    for (const fs::path& p : removed)
        names.push_back(p.filename().string());
    std::sort(names.begin(), names.end());
    std::vector<std::string> expected = stale;
    std::sort(expected.begin(), expected.end());
    CHECK(names == expected);
    for (const auto& name : kept) {
        INFO(name);
        CHECK(fs::exists(dir / name));
    }
    CHECK(fs::is_directory(dir / (".d.tmp." + dead)));
    CHECK(fs::is_symlink(dir / (".l.tmp." + dead + ".json")));
    CHECK(vri::removeStaleTempFiles(dir / "no-such-folder").empty());
}
