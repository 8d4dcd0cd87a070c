#pragma once
// Private to the readers built on OpenImageIO (images, TIFF stacks): opening a file and its messages.
// Includes OpenImageIO, so only io/ sources may include it.
#include <filesystem>
#include <memory>
#include <string>

#include <OpenImageIO/imageio.h>

namespace vri::detail {

// OpenImageIO's messages may span lines; vri's errors are one line.
std::string oneLine(std::string message);

// Throws vri::Error "PATH: no such file" or "PATH: cannot read image: ...".
std::unique_ptr<OIIO::ImageInput> openImageInput(const std::filesystem::path& path);

}  // namespace vri::detail
