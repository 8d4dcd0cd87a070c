#pragma once
// The functions of the OpenImageIO module (oiio_module.h's OiioModule), one file each; only the module's
// own sources include this.
#include "libvri/io/io_module.h"  // caughtMessage: nothing thrown crosses the module's boundary
#include "libvri/io/oiio_module.h"

namespace vri::detail::oiio {

std::string readImage(const std::filesystem::path& path, Image& image);
std::string readImageMetadata(const std::filesystem::path& path, ImageMetadata& metadata);
std::string encodeImage(const std::filesystem::path& path, const Image& image, std::string& bytes);
std::string readTiffStack(const std::filesystem::path& path, const TiffStackRead& read);

}  // namespace vri::detail::oiio
