#include "libvri/io/oiio_module.h"

#include "libvri/io/io_module.h"

namespace vri::detail {

const OiioModule& oiioModule(const std::filesystem::path& path, std::string_view doing) {
    return moduleTable<OiioModule>(kOiioModuleFile, kOiioModuleEntry, path, doing,
                                   "this format needs vri's OpenImageIO module");
}

}  // namespace vri::detail
