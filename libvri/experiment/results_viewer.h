#pragma once
// The results viewer: static pages a browser opens from the file system, no server and nothing fetched
// (tools/viewer/ holds its script and style, embedded in vri-run and written to <results>/viewer/).
//  - <results>/index.html lists the experiments in the gallery's order (gallery.h), linked to their pages.
//  - <results>/<experiment>/index.html holds the experiment as JSON in a <script type="application/json">
//    element (scriptSafeJson: no name can close it): title, what the paper says, how ours agrees, the commit,
//    the render and difference-image grids (gallery_grid.h) with each image's PNG, size and, for a render
//    made as an EXR, its float data's script, the heat maps' scales, the tables' Markdown, the figures and
//    the notes. The script draws the grids, two images picked to swipe, flip, set side by side or
//    subtract, zoomed to single pixels with each one's float values, exposure and gamma.
//  - <results>/<experiment>/viewer-data/<id>.js: a render's float pixels (viewer_floats.h), written from
//    its EXR. Like the EXRs they are not kept in git; a page whose data are missing says so and still shows
//    the PNGs.
// The pages depend only on the manifests, tables and PNGs, never on which EXRs are present, so a results
// folder's committed pages are what `vri-run --gallery` makes of it anywhere.
#include <cstddef>
#include <filesystem>
#include <vector>

#include "libvri/experiment/gallery.h"

namespace vri {

// index.html, every experiment's index.html, viewer/vri-viewer.js and viewer/vri-viewer.css.
std::vector<GalleryPage> viewerPages(const std::vector<GalleryEntry>& entries);

// Writes the float data of each render whose EXR is in its experiment's folder and newer than its data
// file; returns how many it wrote.
std::size_t writeViewerFloats(const std::vector<GalleryEntry>& entries);

}  // namespace vri
