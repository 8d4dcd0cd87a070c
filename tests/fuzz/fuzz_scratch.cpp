#include "fuzz_scratch.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <system_error>

#include "libvri/io/volume_io.h"
#include "libvri/util/error.h"

namespace vri::fuzz {

namespace fs = std::filesystem;

namespace {

void writeBytes(const fs::path& path, const void* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
        std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
        std::abort();  // not a finding of the parser: the harness cannot run
    }
}

fs::path makeScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "vri-fuzz.XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
        std::perror("fuzz: mkdtemp");
        std::abort();
    }
    const fs::path dir = pattern;
    unsigned char voxels[512];
    for (unsigned i = 0; i < sizeof voxels; ++i)
        voxels[i] = static_cast<unsigned char>((i * 37 + i / 64 * 11) % 256);
    writeBytes(dir / "data.raw", voxels, sizeof voxels);
    return dir;
}

}  // namespace

const fs::path& scratchDir() {
    static const fs::path dir = makeScratchDir();
    static const bool removeAtExit = [] {
        return std::atexit([] {
                   std::error_code ignored;
                   fs::remove_all(dir, ignored);
               }) == 0;
    }();
    (void)removeAtExit;
    return dir;
}

fs::path writeInput(const char* name, const std::uint8_t* data, std::size_t size) {
    const fs::path path = scratchDir() / name;
    writeBytes(path, data, size);
    return path;
}

void readInputAsVolume(const char* name, const std::uint8_t* data, std::size_t size) {
    const fs::path path = writeInput(name, data, size);
    try {
        readVolume(path);
    } catch (const Error&) {
    }
}

}  // namespace vri::fuzz
