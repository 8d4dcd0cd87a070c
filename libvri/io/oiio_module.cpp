#include "libvri/io/oiio_module.h"

#include <dlfcn.h>

#include <vector>

#include "libvri/util/error.h"

// The module's folder relative to a tool's bin/ (the build tree puts it in the same place) and where
// `cmake --install` puts it; both come from the build (libvri/CMakeLists.txt).
#ifndef VRI_MODULE_RELATIVE_DIR
#error "VRI_MODULE_RELATIVE_DIR must name the module's folder relative to bin/"
#endif
#ifndef VRI_MODULE_INSTALL_DIR
#error "VRI_MODULE_INSTALL_DIR must name the installed module's folder"
#endif

namespace vri::detail {

namespace fs = std::filesystem;

namespace {

// Where to look, in order: beside the binary that holds this code (a tool, the Python module, a user's
// program: <its folder>/../lib/vri), beside the running executable, and the installed module's folder.
std::vector<fs::path> candidateFiles() {
    std::vector<fs::path> folders;
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&oiioModule), &info) && info.dli_fname && *info.dli_fname)
        folders.push_back(fs::path(info.dli_fname).parent_path());
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    if (!error) folders.push_back(self.parent_path());
    std::vector<fs::path> files;
    for (const fs::path& folder : folders) files.push_back(folder / VRI_MODULE_RELATIVE_DIR / kOiioModuleFile);
    files.push_back(fs::path(VRI_MODULE_INSTALL_DIR) / kOiioModuleFile);
    return files;
}

struct Loaded {
    const OiioModule* module = nullptr;
    std::string failure;  // why none could be loaded
};

Loaded load() {
    Loaded loaded;
    std::string tried;
    for (const fs::path& file : candidateFiles()) {
        std::error_code error;
        if (!fs::is_regular_file(file, error)) {
            tried += (tried.empty() ? "" : ", ") + file.lexically_normal().string();
            continue;
        }
        void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
        const char* why = handle ? nullptr : dlerror();
        auto* entry = handle ? reinterpret_cast<const OiioModule* (*)()>(dlsym(handle, kOiioModuleEntry)) : nullptr;
        if (entry) {
            loaded.module = entry();  // the handle stays open for the process's life
            return loaded;
        }
        if (handle) dlclose(handle);
        loaded.failure = file.string() + (why ? ": " + std::string(why) : ": no " + std::string(kOiioModuleEntry) +
                                                                              " (a module of another vri build)");
        return loaded;
    }
    loaded.failure = std::string(kOiioModuleFile) + " not found (looked for " + tried + ")";
    return loaded;
}

}  // namespace

const OiioModule& oiioModule(const fs::path& path, std::string_view doing) {
    static const Loaded loaded = load();  // thread-safe, once
    if (!loaded.module)
        throw Error(path.string() + ": cannot " + std::string(doing) +
                    ": this format needs vri's OpenImageIO module: " + loaded.failure);
    return *loaded.module;
}

void requireModuleSuccess(const std::string& message) {
    if (!message.empty()) throw Error(message);
}

}  // namespace vri::detail
