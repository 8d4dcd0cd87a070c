#include "libvri/io/oiio_module.h"

#include "libvri/io/io_module.h"
#include "libvri/util/error.h"

namespace vri::detail {

const OiioModule& oiioModule(const std::filesystem::path& path, std::string_view doing) {
    struct Loaded {
        const OiioModule* module = nullptr;
        std::string failure;
    };
    static const Loaded loaded = [] {  // thread-safe, once
        Loaded l;
        l.module = static_cast<const OiioModule*>(loadModuleTable(kOiioModuleFile, kOiioModuleEntry, l.failure));
        return l;
    }();
    if (!loaded.module)
        throw Error(path.string() + ": cannot " + std::string(doing) +
                    ": this format needs vri's OpenImageIO module: " + loaded.failure);
    return *loaded.module;
}

}  // namespace vri::detail
