#include "libvri/io/io_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <vector>

#include "libvri/util/error.h"

// The modules' folder relative to a tool's bin/ (the build tree puts them in the same place) and where
// `cmake --install` puts them; both come from the build (libvri/CMakeLists.txt).
#ifndef VRI_MODULE_RELATIVE_DIR
#error "VRI_MODULE_RELATIVE_DIR must name the modules' folder relative to bin/"
#endif
#ifndef VRI_MODULE_INSTALL_DIR
#error "VRI_MODULE_INSTALL_DIR must name the installed modules' folder"
#endif

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> candidateFiles(const char* file) {
    std::vector<fs::path> folders;
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&loadModuleTable), &info) && info.dli_fname && *info.dli_fname)
        folders.push_back(fs::path(info.dli_fname).parent_path());
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    if (!error) folders.push_back(self.parent_path());
    std::vector<fs::path> files;
    for (const fs::path& folder : folders) files.push_back(folder / VRI_MODULE_RELATIVE_DIR / file);
    // The installed Python module, in <prefix>/lib/pythonX.Y/site-packages: two folders deeper than bin/.
    if (!folders.empty()) files.push_back(folders.front() / ".." / ".." / VRI_MODULE_RELATIVE_DIR / file);
    files.push_back(fs::path(VRI_MODULE_INSTALL_DIR) / file);
    return files;
}

}  // namespace

const void* loadModuleTable(const char* file, const char* entry, std::string& failure) {
    std::string tried;
    for (const fs::path& candidate : candidateFiles(file)) {
        std::error_code error;
        if (!fs::is_regular_file(candidate, error)) {
            tried += (tried.empty() ? "" : ", ") + candidate.lexically_normal().string();
            continue;
        }
        void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        const char* why = handle ? nullptr : dlerror();
        auto* table = handle ? reinterpret_cast<const void* (*)()>(dlsym(handle, entry)) : nullptr;
        if (table) return table();  // the handle stays open for the process's life
        if (handle) dlclose(handle);
        failure = candidate.string() +
                  (why ? ": " + std::string(why) : ": no " + std::string(entry) + " (a module of another vri build)");
        return nullptr;
    }
    failure = std::string(file) + " not found (looked for " + tried + ")";
    return nullptr;
}

void requireModuleSuccess(const std::string& message) {
    if (!message.empty()) throw Error(message);
}

}  // namespace vri::detail
