#pragma once
// Private to the TIFF stack reader: how many pages a TIFF's own chain of image file directories (IFDs)
// holds, counted from the file's bytes. OpenImageIO's seek to a page fails alike at the end of the chain
// and at a directory that a cut file no longer holds, so a truncated stack read as fewer pages; the chain,
// walked here, tells the two apart.
#include <filesystem>

namespace vri::detail {

// The most pages a stack may have: a longer chain is refused.
inline constexpr int kMaxTiffPages = 1 << 20;

// The number of IFDs chained from the header of the classic or BigTIFF file `path`. Throws vri::Error
// "<path>: ..." when the header is not TIFF's, or an IFD (naming its page) starts or ends beyond the
// file's end, the chain loops back to an earlier page, or it holds more than kMaxTiffPages.
int tiffPageCount(const std::filesystem::path& path);

}  // namespace vri::detail
