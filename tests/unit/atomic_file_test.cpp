#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "file_bytes.h"
#include "scoped_environment.h"
#include "temp_dir.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"

namespace {

namespace fs = std::filesystem;
using vri::test::readBytes;

std::set<std::string> entries(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.insert(entry.path().filename().string());
    return names;
}

// The two ways bytes reach a target: directly, and through a writer that needs a file of its own.
void writeBoth(const fs::path& target, const std::string& text, bool throughFile) {
    if (!throughFile) return vri::writeTextFile(target, text);
    vri::writeAtomically(target, [&](const fs::path& tmp) { std::ofstream(tmp, std::ios::binary) << text; });
}

// Reads everything written to a FIFO, on its own thread, from the moment it is started.
class FifoReader {
public:
    explicit FifoReader(const fs::path& fifo) : thread_([this, fifo] { received_ = readBytes(fifo); }) {}
    std::string received() {
        thread_.join();
        return received_;
    }

private:
    std::string received_;
    std::thread thread_;
};

// Points the process's stdout at `file` while it lives.
class StdoutTo {
public:
    explicit StdoutTo(const fs::path& file) : saved_(::dup(STDOUT_FILENO)) {
        std::cout.flush();
        std::fflush(stdout);
        const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, STDOUT_FILENO);
        ::close(fd);
    }
    ~StdoutTo() {
        ::dup2(saved_, STDOUT_FILENO);
        ::close(saved_);
    }
    StdoutTo(const StdoutTo&) = delete;
    StdoutTo& operator=(const StdoutTo&) = delete;

private:
    int saved_;
};

// A character device of our own, beside the test's files (mknod needs root); nullopt where it cannot be made.
std::optional<fs::path> privateDevice(const fs::path& dir, const char* name, unsigned minor) {
    if (::geteuid() != 0) return std::nullopt;
    const fs::path node = dir / name;
    if (::mknod(node.c_str(), S_IFCHR | 0666, ::makedev(1, minor)) != 0) return std::nullopt;
    return node;
}

bool isCharDevice(const fs::path& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}


}  // namespace

TEST_CASE("output: a missing path is created, its missing folders too, with no temporary file left") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        const fs::path target = dir / (throughFile ? "b" : "a") / "deep" / "out.csv";
        writeBoth(target, "x,y\n", throughFile);
        CHECK(readBytes(target) == "x,y\n");
        CHECK(entries(target.parent_path()) == std::set<std::string>{"out.csv"});
    }
}

TEST_CASE("output: a regular file is replaced, keeping its permission bits") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        const fs::path target = dir / "out.json";
        std::ofstream(target) << "old, and longer than the new content";
        fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
        writeBoth(target, "new", throughFile);
        CHECK(readBytes(target) == "new");
        CHECK(fs::status(target).permissions() ==
              (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
        CHECK(entries(dir.path) == std::set<std::string>{"out.json"});
    }
}

TEST_CASE("output: a symlink stays a link and its target is replaced, through chains and relative links") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        fs::create_directories(dir / "data");
        std::ofstream(dir / "data" / "real.exr") << "old";
        fs::create_symlink("data/real.exr", dir / "first.exr");     // relative to the link's folder
        fs::create_symlink(dir / "first.exr", dir / "second.exr");  // absolute, to another link
        writeBoth(dir / "second.exr", "new", throughFile);
        CHECK(fs::is_symlink(dir / "second.exr"));
        CHECK(fs::is_symlink(dir / "first.exr"));
        CHECK(readBytes(dir / "data" / "real.exr") == "new");
        CHECK(entries(dir / "data") == std::set<std::string>{"real.exr"});
        fs::remove_all(dir / "data");
        fs::remove(dir / "first.exr");
        fs::remove(dir / "second.exr");
    }
}

TEST_CASE("output: a dangling symlink gets its target created and stays a link") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        fs::create_symlink("made/target.csv", dir / "link.csv");
        writeBoth(dir / "link.csv", "made", throughFile);
        CHECK(fs::is_symlink(dir / "link.csv"));
        CHECK(readBytes(dir / "made" / "target.csv") == "made");
        CHECK(entries(dir / "made") == std::set<std::string>{"target.csv"});
        fs::remove_all(dir / "made");
        fs::remove(dir / "link.csv");
    }
}

TEST_CASE("output: a FIFO with a reader receives the bytes and stays a FIFO; nothing is left beside it or in TMPDIR") {
    vri::test::TempDir dir("atomic-file");
    vri::test::TempDir tmp("atomic-file-tmpdir");
    const test::ScopedEnvironment tmpDir("TMPDIR", tmp.path.string());  // the temporary files go there
    const fs::path fifo = dir / "pipe.png";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const std::string big(3 << 20, 'v');  // more than a pipe holds, and more than one copy chunk
    for (const bool throughFile : {false, true}) {
        FifoReader reader(fifo);
        writeBoth(fifo, big, throughFile);
        CHECK(reader.received() == big);
        CHECK(fs::is_fifo(fs::symlink_status(fifo)));
        CHECK(entries(dir.path) == std::set<std::string>{"pipe.png"});
        CHECK(entries(tmp.path).empty());
    }
}

TEST_CASE("output: '-' writes to stdout, after what the process printed before") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        {
            const StdoutTo redirect(dir / "captured");
            std::cout << "before;";
            writeBoth("-", "the bytes", throughFile);
        }
        CHECK(readBytes(dir / "captured") == "before;the bytes");
        CHECK(entries(dir.path) == std::set<std::string>{"captured"});
    }
}

TEST_CASE("output: a link to an open pipe (as /dev/stdout is) writes into the pipe") {
    vri::test::TempDir dir("atomic-file");
    for (const bool throughFile : {false, true}) {
        int ends[2];
        REQUIRE(::pipe(ends) == 0);
        const fs::path link = dir / "stdout.csv";
        fs::create_symlink("/proc/self/fd/" + std::to_string(ends[1]), link);
        writeBoth(link, "through the pipe", throughFile);
        ::close(ends[1]);
        char received[64] = {};
        CHECK(::read(ends[0], received, sizeof received) == 16);
        ::close(ends[0]);
        CHECK(std::string(received) == "through the pipe");
        CHECK(fs::is_symlink(link));
        CHECK(entries(dir.path) == std::set<std::string>{"stdout.csv"});
        fs::remove(link);
    }
}

TEST_CASE("output: a character device is written in place and stays a device") {
    vri::test::TempDir dir("atomic-file");
    const std::optional<fs::path> null = privateDevice(dir.path, "null", 3);
    if (!null) {
        MESSAGE("skipped: making a private character device (mknod) needs root");
        return;
    }
    for (const bool throughFile : {false, true}) {
        writeBoth(*null, "discarded", throughFile);
        CHECK(isCharDevice(*null));
        CHECK(entries(dir.path) == std::set<std::string>{"null"});
    }
}

TEST_CASE("output: a device that refuses the bytes is an error naming the path, and stays a device") {
    vri::test::TempDir dir("atomic-file");
    const std::optional<fs::path> full = privateDevice(dir.path, "full", 7);  // /dev/full's numbers: ENOSPC
    if (!full) {
        MESSAGE("skipped: making a private character device (mknod) needs root");
        return;
    }
    for (const bool throughFile : {false, true}) {
        CHECK_THROWS_WITH_AS(writeBoth(*full, "no room", throughFile),
                             doctest::Contains((full->string() + ": cannot write: No space left on device").c_str()),
                             vri::Error);
        CHECK(isCharDevice(*full));
        CHECK(entries(dir.path) == std::set<std::string>{"full"});
    }
}

TEST_CASE("output: a directory is an error naming the path, and nothing is written") {
    vri::test::TempDir dir("atomic-file");
    fs::create_directory(dir / "out.exr");
    for (const bool throughFile : {false, true}) {
        CHECK_THROWS_WITH_AS(
            writeBoth(dir / "out.exr", "x", throughFile),
            doctest::Contains(((dir / "out.exr").string() + ": cannot write: it is a directory").c_str()), vri::Error);
        CHECK(fs::is_directory(dir / "out.exr"));
        CHECK(fs::is_empty(dir / "out.exr"));
        CHECK(entries(dir.path) == std::set<std::string>{"out.exr"});
    }
}

TEST_CASE("output: a file size limit (ulimit -f) is an error; the old file stays and no temporary file is left") {
    vri::test::TempDir dir("atomic-file");
    const fs::path target = dir / "out.raw";
    std::ofstream(target) << "old";
    rlimit saved{};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
    rlimit limited = saved;
    limited.rlim_cur = 4096;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
    const std::string tooBig(10000, 'b');
    for (const bool throughFile : {false, true}) {
        // Through a file, the writer is the one that meets the limit: an unchecked one still must not win.
        if (throughFile)
            CHECK_THROWS_AS(vri::writeAtomically(target,
                                                 [&](const fs::path& tmp) {
                                                     std::ofstream out(tmp, std::ios::binary);
                                                     out << tooBig;
                                                     out.close();
                                                     if (!out) throw vri::Error(target.string() + ": cannot write");
                                                 }),
                            vri::Error);
        else
            CHECK_THROWS_WITH_AS(vri::writeTextFile(target, tooBig),
                                 doctest::Contains((target.string() + ": cannot write: File too large").c_str()),
                                 vri::Error);
        CHECK(readBytes(target) == "old");
        CHECK(entries(dir.path) == std::set<std::string>{"out.raw"});
    }
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &saved) == 0);
}

TEST_CASE("output: a writer that leaves no file is an error, not an empty output") {
    vri::test::TempDir dir("atomic-file");
    const fs::path target = dir / "figure.png";
    CHECK_THROWS_WITH_AS(vri::writeAtomically(target, [](const fs::path&) {}),
                         doctest::Contains((target.string() + ": cannot write: the writer produced no file").c_str()),
                         vri::Error);
    CHECK(entries(dir.path).empty());
}

TEST_CASE("output: outputs written together: when one fails, none is replaced") {
    vri::test::TempDir dir("atomic-file");
    std::ofstream(dir / "v.raw") << "old raw";
    std::ofstream(dir / "v.nhdr") << "old header";
    const std::string bigHeader(10000, 'h');
    SUBCASE("the second cannot be written (a file size limit)") {
        rlimit saved{};
        REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
        rlimit limited = saved;
        limited.rlim_cur = 4096;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
        const vri::OutputBytes files[] = {{dir / "v.raw", "new raw"}, {dir / "v.nhdr", bigHeader}};
        CHECK_THROWS_WITH_AS(vri::writeTogether(files),
                             doctest::Contains(((dir / "v.nhdr").string() + ": cannot write: File too large").c_str()),
                             vri::Error);
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &saved) == 0);
    }
    SUBCASE("the second is the first again, through a link (they would share one temporary file)") {
        std::filesystem::create_symlink("v.raw", dir / "link.raw");
        const vri::OutputBytes files[] = {{dir / "v.raw", "new raw"}, {dir / "link.raw", "new link"}};
        CHECK_THROWS_WITH_AS(vri::writeTogether(files),
                             doctest::Contains(((dir / "link.raw").string() + ": cannot write: it is also " +
                                                (dir / "v.raw").string() + ", written by the same command")
                                                   .c_str()),
                             vri::Error);
        std::filesystem::remove(dir / "link.raw");
    }
    SUBCASE("the second has no place to go (a file where its folder should be)") {
        const vri::OutputBytes files[] = {{dir / "v.raw", "new raw"}, {dir / "v.nhdr" / "inner", "new header"}};
        CHECK_THROWS_WITH_AS(
            vri::writeTogether(files),
            doctest::Contains(((dir / "v.nhdr" / "inner").string() + ": cannot write: Not a directory").c_str()),
            vri::Error);
    }
    CHECK(readBytes(dir / "v.raw") == "old raw");
    CHECK(readBytes(dir / "v.nhdr") == "old header");
    CHECK(entries(dir.path) == std::set<std::string>{"v.nhdr", "v.raw"});
}
