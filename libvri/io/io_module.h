#pragma once
// Modules of vri's own that the io layer loads when a file needs them: OpenImageIO (oiio_module.h) and
// OpenVDB (vdb_module.h). Linked into every tool, each cost every process its start-up (0.7-1 s for
// OpenImageIO's 260 libraries, 65 ms for OpenVDB's 61,000 symbol relocations) whether it read such a file
// or not. A module exports one versioned entry point returning its table of functions; no exception crosses
// its boundary (each function returns "" or its one-line message). Private to io/.
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "libvri/util/error.h"

namespace vri::detail {

// The table `entry` of the module `file` (libvri-NAME.so), loaded once per process from, in order: beside
// the binary that holds this code (a tool, the Python module, a user's program: <its folder>/../lib/vri),
// beside the running executable, where the installed Python module finds it (<its folder>/../../../lib/vri),
// and the installed modules' folder. nullptr when none loads, `failure` then saying why and where it looked.
const void* loadModuleTable(const char* file, const char* entry, std::string& failure);

// The table of type Table of the module `file`, loaded on first use (once per process). Throws vri::Error
// "PATH: cannot DOING: NEEDS: <why, and where it looked>" when it cannot be loaded.
template <class Table>
const Table& moduleTable(const char* file, const char* entry, const std::filesystem::path& path, std::string_view doing,
                         std::string_view needs) {
    struct Loaded {
        const Table* table = nullptr;
        std::string failure;
    };
    static const Loaded loaded = [&] {  // thread-safe, once
        Loaded l;
        l.table = static_cast<const Table*>(loadModuleTable(file, entry, l.failure));
        return l;
    }();
    if (!loaded.table)
        throw Error(path.string() + ": cannot " + std::string(doing) + ": " + std::string(needs) + ": " +
                    loaded.failure);
    return *loaded.table;
}

// Throws vri::Error(message) unless the module's call succeeded (an empty message).
void requireModuleSuccess(const std::string& message);

// Inside a module: runs `body`; what it throws becomes the returned message.
template <typename Body>
std::string caughtMessage(const char* module, Body&& body) {
    const std::string unknown = std::string("unknown error in vri's ") + module + " module";
    try {
        body();
        return {};
    } catch (const std::exception& e) {
        return *e.what() ? e.what() : unknown;  // "" would read as success
    } catch (...) {
        return unknown;
    }
}

}  // namespace vri::detail
