#pragma once
// OpenEXR files through the OpenEXR library itself: a render's own format, read and written without
// OpenImageIO, whose plug-ins (video, GIS, DICOM, ... 260 shared libraries on Debian) cost every process
// most of a second to load. Private to image_io.cpp; includes no OpenEXR header.
#include <filesystem>
#include <string>

#include "libvri/core/image.h"
#include "libvri/io/image_io.h"

namespace vri::detail {

// Whether the file starts with OpenEXR's magic number (a missing or short file is not one).
bool isExrFile(const std::filesystem::path& path);

// The first part's data window, every channel converted to float, named as the file names them, in
// OpenImageIO's order (R, G, B, A first, then the others as the file sorts them), so that images read the
// same as before this reader existed. Throws vri::Error "PATH: cannot read image: <why>".
Image readExrFile(const std::filesystem::path& path);

// The header's string attributes, in the file's (alphabetical) order.
ImageMetadata readExrMetadata(const std::filesystem::path& path);

// The image as a 32-bit float, ZIP-compressed scanline OpenEXR file, in memory: the caller writes it with
// its checked writes. Channel names from the image; `metadata` as string attributes.
std::string encodeExr(const Image& image, const ImageMetadata& metadata);

}  // namespace vri::detail
