#include "libvri/util/own_folder.h"

#include <system_error>

#include "libvri/util/error.h"

namespace vri {

namespace fs = std::filesystem;

void requireOwnFolder(const fs::path& folder) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(folder, ec);
    if (status.type() == fs::file_type::not_found) return;
    if (ec) throw Error(folder.string() + ": " + ec.message());
    if (fs::is_symlink(status)) {
        const fs::path target = fs::read_symlink(folder, ec);
        throw Error(folder.string() + ": is a symbolic link" + (ec ? "" : " (to " + target.string() + ")") +
                    "; vri-run keeps its own files there and will not write or delete through a link: remove it");
    }
    if (!fs::is_directory(status))
        throw Error(folder.string() + ": is not a folder; vri-run keeps its own files there: remove it");
}

}  // namespace vri
