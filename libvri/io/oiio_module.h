#pragma once
// OpenImageIO as a module vri loads when a file needs it (libvri-oiio.so, libvri/io/oiio/; io_module.h): the
// image formats other than OpenEXR and PNG, and TIFF stacks. Linking OpenImageIO into every tool cost each
// process 0.7-1 s before main() (Debian's build pulls in 260 shared libraries: video, GIS, DICOM, ...), which
// made the start-up, not the rendering, most of a quick experiment's time; renders, their previews and the
// comparisons of renders now read and write through OpenEXR and libpng alone (exr_file.h, png_file.h).
// Private to io/; includes no OpenImageIO header.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "libvri/core/brick_grid.h"
#include "libvri/core/image.h"
#include "libvri/io/image_io.h"
#include "libvri/io/stored_voxels.h"

namespace vri::detail {

// A TIFF stack's pages as the module finds them: one channel each, all of one size and stored type.
struct TiffStackShape {
    int width = 0;
    int height = 0;
    int pages = 0;
    StoredType type = StoredType::UInt8;  // half floats are read as float32, which holds them exactly
};

// What readTiffStack reads of a stack, once every page's shape is checked.
struct TiffStackRead {
    // The voxels [box.lo, box.hi) (x a column, y a row, z a page), box-row after box-row in x-fastest order;
    // every page whole when absent. A run of whole rows at a time is held besides the buffer (about 1 MiB).
    std::optional<VoxelBox> box;
    // The buffer for the box's voxels (read as TiffStackShape's type), given the stack's shape: it checks the
    // sizes (what it throws comes back as the message). nullptr: the shape was all the caller wanted.
    std::function<char*(const TiffStackShape&)> allocate;
    // When set, the buffer holds one page of the box: each page is read into it and then handed to pageRead
    // with its z (a scan of every voxel a page at a time).
    std::function<void(int z)> pageRead;
};

// The module's functions. Each returns "" when it succeeded, else its one-line message, which names the
// file: no exception crosses the module's boundary.
struct OiioModule {
    // Any 2D format OpenImageIO reads: first subimage, top mip level, its data window, as float.
    std::string (*readImage)(const std::filesystem::path& path, Image& image);
    // The header's string attributes.
    std::string (*readImageMetadata)(const std::filesystem::path& path, ImageMetadata& metadata);
    // `image` as float in the format the path's extension names, encoded into `bytes` (formats that cannot
    // encode into memory are refused: their writes could not be checked).
    std::string (*encodeImage)(const std::filesystem::path& path, const Image& image, std::string& bytes);
    // Checks every page's shape, then reads `read.box` of the stack (see TiffStackRead).
    std::string (*readTiffStack)(const std::filesystem::path& path, const TiffStackRead& read);
};

// The entry point the module exports: a versioned name, so that a module of another build is not taken.
inline constexpr const char* kOiioModuleEntry = "vri_oiio_module_2";
inline constexpr const char* kOiioModuleFile = "libvri-oiio.so";

// The module, loaded on first use (once per process). Throws vri::Error "PATH: cannot <doing>: ..." naming
// where the module was looked for when it cannot be loaded.
const OiioModule& oiioModule(const std::filesystem::path& path, std::string_view doing);

}  // namespace vri::detail
