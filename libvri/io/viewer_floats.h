#pragma once
// A render's float pixels as a script the results viewer loads beside its page (results_viewer.h): a page
// opened from the file system may not read other files, but it may run a <script src>, so the data come
// as one call,
//   vriViewerFloats({"id": ID, "width": W, "height": H, "channels": [...], "encoding": "f32le-zlib-base64",
//                    "data": "..."});
// with `data` the pixels as little-endian 32-bit floats (interleaved channels, row 0 at the top, exactly the
// EXR's values), compressed by zlib (RFC 1950, what a browser's DecompressionStream("deflate") reads) and
// base64-encoded. Float32, not half: vri's errors of 1e-4 around 0.5 are below a half float's step there.
#include <string>

#include "libvri/core/image.h"

namespace vri {

std::string viewerFloatsScript(const std::string& id, const Image& image);

}  // namespace vri
